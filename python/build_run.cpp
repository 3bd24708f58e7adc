// build in-process: process::BuildPlan as a Python class made of the bound structs (the powder's
// Scene, the SpreadSettings, the SinterScene, a Hatch, the FusionPolicy) and process::build_layer
// layer after layer on a Bed, with the GIL released, as apps/build.cpp runs it less its option
// parsing, pictures and report file. Each layer's files go to the plan's folder (build_layer
// writes them); the powder left, the reports, the spread's state and the part's record come back.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <tuple>
#include <vector>

#include "bed_dict.hpp"
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
#include "powderbed/thermal/part_porosity.hpp"
#include "powderbed/thermal/solver.hpp"

namespace py = pybind11;

namespace powderbed::python {

namespace th = thermal;

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
  std::vector<std::string> warnings;
  plan.warning = [&warnings](const std::string& message) { warnings.push_back(message); };
  const std::uint64_t first = (spread_state ? spread_state->layers_done : 0) + 1;
  py::list reports;
  {
    py::gil_scoped_release release;
    plan.table = th::read_material_table(bed::material_path(plan.scan.material_table, "material_table"));
    record = part_to_continue(plan, bed.domain, spread_state, std::move(record));
    process::check_layers(plan, bed.domain, first, layers);
    make_folder(plan.out);
  }
  for (std::uint64_t layer = first; layer < first + layers; ++layer) {
    const process::Progress spread_progress = stage_progress(progress, layer, "spread");
    const process::Progress scan_progress = stage_progress(progress, layer, "scan");
    process::LayerReport report;
    {
      py::gil_scoped_release release;
      report = process::build_layer(plan, bed, spread_state, *record, layer, spread_progress, scan_progress);
    }
    for (const std::string& message : warnings) warn("build: " + message);
    warnings.clear();
    reports.append(layer_report_dict(report));
  }
  return py::make_tuple(bed_to_dict(bed), reports, py::cast(*spread_state), py::cast(*record));
}

}  // namespace

void bind_build(py::module_& m) {
  bind_plan(m);
  m.def("build", &build, py::arg("bed"), py::arg("plan"), py::arg("layers"), py::arg("state"),
        py::arg("part"), py::arg("supply"), py::arg("progress"));
}

}  // namespace powderbed::python
