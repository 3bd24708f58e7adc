// build in-process: process::BuildPlan as a Python class made of the bound structs (the powder's
// Scene, the SpreadSettings, the SinterScene, a Hatch, the FusionPolicy) and process::build_layer
// layer after layer on a Bed, with the GIL released, as apps/build.cpp runs it less its option
// parsing, pictures and report file (build); and a build scene file read by the program's own
// option table (apps/build_scene.hpp), its layers run the same way and its report written by the
// program's writer (build_scene). Each layer's files go to the plan's folder (build_layer writes
// them); the powder left, the reports, the spread's state and the part's record come back.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <tuple>
#include <vector>

#include <omp.h>

#include "bed_dict.hpp"
#include "build_scene.hpp"
#include "bindings.hpp"
#include "build_report.hpp"
#include "powderbed/dem/contact_provenance.hpp"
#include "gil_callback.hpp"
#include "python_warning.hpp"
#include "struct_binding.hpp"
#include "supply_maker.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/material_file.hpp"
#include "powderbed/process/build_layer.hpp"
#include "powderbed/process/build_plan.hpp"
#include "powderbed/process/build_report.hpp"
#include "powderbed/thermal/part_porosity.hpp"
#include "powderbed/thermal/solver.hpp"

namespace py = pybind11;

namespace powderbed::python {

namespace th = thermal;
namespace po = app::po;

namespace {

void bind_plan(py::module_& m) {
  using F = process::FusionPolicy;
  StructBinding<F>(m, "FusionPolicy", "How a scanned layer joins the solid (build_plan.hpp).")
      .field("melt_fraction", &F::melt_fraction, "of the enthalpy of melting: 0.5 fuses what reached T_m")
      .field("capture", &F::capture, "powder overlapped by more than this share of r joins the solid")
      .field("level", &F::level, "levelling length, m (< 0: half the beam radius)")
      .done();
  using P = process::BuildPlan;
  StructBinding<P>(m, "BuildPlan",
                   "A build's plan (process::BuildPlan): the powder's Scene, the recoater's "
                   "SpreadSettings (one layer a call), the scan's SinterScene and its Hatch, the "
                   "FusionPolicy and the folder the layers' files go to.")
      .field("scene", &P::scene, "Scene (or a dict of its fields)")
      .field("spread", &P::spread, "SpreadSettings (or a dict of its fields)")
      .field("finest_diameter", &P::finest_diameter, "of the supply, m: no layer thinner")
      .field("scan", &P::scan, "SinterScene (or a dict of its fields)")
      .field("hatch", &P::hatch, "Hatch turned per layer, or None: every layer scans scan.scan_path")
      .field("fusion", &P::fusion, "FusionPolicy (or a dict of its fields)")
      .field("out", &P::out, "the folder of the layers' files (made when missing)")
      .field("snapshots", &P::snapshots, "scan snapshots a layer (0: none)")
      .done();
  py::class_<th::PartRecord>(m, "PartRecord",
                             "The part's record so far: pass it to the next build of the Bed and "
                             "SpreadState it returned to continue.")
      .def_readonly("layers", &th::PartRecord::layers);
}

// The part's record to go on from: `given` checked against the scan's grid on the bed's plate,
// or a new one on it (apps/build.cpp check_scan).
th::PartRecord part_to_continue(const process::BuildPlan& plan, const bed::Domain& box,
                                const std::optional<dem::SpreadState>& state,
                                std::optional<th::PartRecord> given) {
  bed::Bed empty;
  empty.domain = box;
  const th::Sinter probe(empty, process::scan_for_layer(plan, 1), plan.table,
                         state ? state->floor.z : th::TopHeight{});
  if (!given) return th::part_record(probe.grid());
  th::check_part_grid(*given, probe.grid());
  return *given;
}

// A stage's progress as the Python callable hears it: {"layer", "stage", "fraction"}; without
// one, none.
process::Progress stage_progress(const py::object& progress, std::uint64_t layer, const char* stage) {
  if (!given(progress)) return {};
  return [fn = py::handle(progress), layer, stage](double fraction, const std::string&) {
    call_with_gil(fn, [=] {
      py::dict d;
      d["layer"] = layer;
      d["stage"] = stage;
      d["fraction"] = fraction;
      return std::make_tuple(d);
    });
  };
}

// Layers `first` on, `layers` of them, built on `bed` with the GIL released while each runs, as
// the program builds them; a layer's warnings (plan.warning) come out as RuntimeWarnings after it.
std::vector<process::LayerReport> run_layers(process::BuildPlan& plan, bed::Bed& bed,
                                             std::optional<dem::SpreadState>& state,
                                             th::PartRecord& part, std::uint64_t first,
                                             std::uint64_t layers, const py::object& progress) {
  std::vector<std::string> warnings;
  plan.warning = [&warnings](const std::string& message) { warnings.push_back(message); };
  std::vector<process::LayerReport> reports;
  for (std::uint64_t layer = first; layer < first + layers; ++layer) {
    const process::Progress spread_progress = stage_progress(progress, layer, "spread");
    const process::Progress scan_progress = stage_progress(progress, layer, "scan");
    {
      py::gil_scoped_release release;
      reports.push_back(
          process::build_layer(plan, bed, state, part, layer, spread_progress, scan_progress));
    }
    for (const std::string& message : warnings) warn("build: " + message);
    warnings.clear();
  }
  plan.warning = nullptr;  // `warnings` ends here
  return reports;
}

void make_folder(const std::string& out) {
  if (out.empty()) throw InputError("out: '' (accepted: the folder for the layers' files)");
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) throw InputError(fmt::format("out: cannot make the folder '{}': {}", out, ec.message()));
}

py::tuple build(const py::dict& bed_fields, process::BuildPlan plan, std::uint64_t layers,
                const py::object& state, const py::object& part, const py::object& supply,
                const py::object& progress) {
  if (layers < 1) throw InputError("layers: 0 (accepted: N >= 1)");
  bed::Bed bed = bed_from_dict(bed_fields);
  std::optional<dem::SpreadState> spread_state;
  if (!state.is_none()) spread_state = state.cast<dem::SpreadState>();
  std::optional<th::PartRecord> record;
  if (!part.is_none()) record = part.cast<th::PartRecord>();
  plan.spread.layers = 1;  // one layer a call (build_plan.hpp)
  if (given(supply)) plan.spread.supply = supply_maker(supply);
  plan.spread_provenance.stage = "build";
  plan.spread_provenance.contact = dem::contact_provenance(plan.scene, plan.spread.young_scale);
  const std::uint64_t first = (spread_state ? spread_state->layers_done : 0) + 1;
  {
    py::gil_scoped_release release;
    plan.table = th::read_material_table(bed::material_path(plan.scan.material_table, "material_table"));
    record = part_to_continue(plan, bed.domain, spread_state, std::move(record));
    process::check_layers(plan, bed.domain, first, layers);
    make_folder(plan.out);
  }
  py::list reports;
  for (const process::LayerReport& report :
       run_layers(plan, bed, spread_state, *record, first, layers, progress))
    reports.append(layer_report_dict(report));
  return py::make_tuple(bed_to_dict(bed), reports, py::cast(*spread_state), py::cast(*record));
}

// The options of the program build that the in-process build leaves to it: what the program
// prints instead of building (help, version, print-config), its --json summary (build_scene
// returns the report) and its process map (map.power, map.speed, map.hatch).
constexpr const char* kProgramOnly[] = {"help", "version", "print-config", "json",
                                        "map.power", "map.speed", "map.hatch"};

[[noreturn]] void refuse_program_only(const std::string& name) {
  throw InputError(fmt::format("{}: the program build's option (accepted: the build's scene "
                               "options; powderbed.run(\"build\", ...) runs the program)",
                               name));
}

// Refused by name before the options are parsed, so that nothing is printed; `args` are the
// words of the command line, "--name value" or "--name=value" (a value such as spread_args'
// "--thermo 0" is not an option of the build's).
void refuse_program_words(const std::vector<std::string>& args) {
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& word = args[k];
    if (word.rfind("--", 0) != 0) continue;
    const std::size_t equals = word.find('=');
    const std::string name = word.substr(2, equals - 2);
    for (const char* only : kProgramOnly)
      if (name == only) refuse_program_only(name);
    if (equals == std::string::npos) ++k;  // its value
  }
}

// ... and once parsed, what the scene file set. Pictures are drawn by a script the program
// starts: none here, as with the program's --pictures false; asked for, they are refused.
void refuse_program_scene(const po::variables_map& vm) {
  for (const char* only : kProgramOnly)
    if (vm.count(only)) refuse_program_only(only);
  if (!vm["pictures"].defaulted() && vm["pictures"].as<bool>())
    throw InputError("pictures: true (accepted: false; the in-process build draws none: "
                     "powderbed.run(\"build\", ...) draws them, or scripts/plot_build_layer.py "
                     "from a layer's scan file)");
}

// The build's options parsed as the program parses its command line "build `args`..." (the
// program's option table and checks, apps/build_scene.hpp) into the plan and what it starts
// from; a Boost error becomes the one line the program prints (less its "build: ").
app::BuildStart start_scene(const std::vector<std::string>& args) {
  refuse_program_words(args);
  std::vector<std::string> words{"build"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  const int argc = static_cast<int>(argv.size());
  po::options_description desc("build options (SI units)");
  app::add_build_options(desc);
  po::variables_map vm;
  try {
    if (!app::parse_options("build", app::kBuildUsage, desc, {}, argc, argv.data(), vm))
      refuse_program_only("help");  // not reached: refuse_program_words refused what prints
  } catch (const po::error& e) {
    throw InputError(fmt::format("{} (see build --help)", e.what()));
  }
  refuse_program_scene(vm);
  return app::start_build(vm, app::read_build(vm, argc, argv.data()));
}

// OpenMP's default team as it was: read_build makes the team of --threads (the idle cores by
// default) the default, which would otherwise stay for the module's later runs.
struct KeepThreadTeam {
  int team = omp_get_max_threads();
  ~KeepThreadTeam() { omp_set_num_threads(team); }
};

// build from a scene file, as the program build runs "build `args`...": the report (build.json's
// text, which it writes too), the powder left, the spread's state, the part's record and the plan.
py::tuple build_scene(const std::vector<std::string>& args, const py::object& progress) {
  const KeepThreadTeam keep;
  app::BuildStart s;
  {
    py::gil_scoped_release release;
    s = start_scene(args);
  }
  process::BuildPlan& plan = s.b.plan;
  const app::OutFolderGuard guard{plan.out, app::make_out(plan.out)};
  const auto started = std::chrono::steady_clock::now();
  std::vector<process::ReportedLayer> reports;
  for (process::LayerReport& r : run_layers(plan, s.bed, s.state, s.part, s.first, s.layers, progress))
    reports.push_back({std::move(r), {}});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string json = process::write_build_report(
      reports, {s.state->layers_done, s.first, s.bed.n(), wall, plan.out});
  return py::make_tuple(bed_to_dict(s.bed), py::module_::import("json").attr("loads")(json),
                        py::cast(*s.state), py::cast(s.part), py::cast(plan));
}

}  // namespace

void bind_build(py::module_& m) {
  bind_plan(m);
  m.def("build", &build, py::arg("bed"), py::arg("plan"), py::arg("layers"), py::arg("state"),
        py::arg("part"), py::arg("supply"), py::arg("progress"));
  m.def("build_scene", &build_scene, py::arg("args"), py::arg("progress"));
}

}  // namespace powderbed::python
