#include "build_scene.hpp"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <unistd.h>

#include "common/threads.hpp"
#include "deposit_spread.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/temp_files.hpp"
#include "powderbed/thermal/solver.hpp"
#include "sinter_options.hpp"
#include "spread_engine_liggghts.hpp"

namespace powderbed::app {

namespace fs = std::filesystem;
namespace th = thermal;

const char* const kBuildUsage =
    "build --config BUILD.ini | --spread SPREAD.ini --sinter SINTER.ini --seed S --out DIR "
    "[--layers N] [--in DIR/layer-NNN.h5] [--spread-args \"...\"] [--sinter-args \"...\"] "
    "[--fuse.melt-fraction F] [--snapshots K] [--pictures false] [--spread-engine liggghts [--mpi N]] "
    "[--map.power P1,P2,... --map.speed V1,V2,... [--map.hatch H1,...]] [--json]";

void add_build_options(po::options_description& desc) {
  add_common_options(desc);
  add_threads_option(desc);
  add_progress_option(desc);
  add_spread_engine_options(desc);
  desc.add_options()
      ("spread", po::value<std::string>(),
       "deposit recoater scene of every layer's spread (recoater.tool; relative: to the build "
       "scene's folder)")
      ("sinter", po::value<std::string>(),
       "sinter scene of every layer's scan (a hatch turns by scan.rotation per layer; relative: "
       "to the build scene's folder)")
      ("spread-args", po::value<std::string>()->default_value(""),
       "options for the spread stage, as deposit takes them (e.g. \"--recoater.speed 0.2\")")
      ("sinter-args", po::value<std::string>()->default_value(""),
       "options for the scan stage, as sinter takes them (e.g. \"--power 250\")")
      ("layers", po::value<std::uint64_t>()->default_value(1),
       "layers to build (with --in: after the ones its file has done)")
      ("seed", po::value<std::uint64_t>(), "random seed of the supplies")
      ("out", po::value<std::string>(), "folder for the layers' files and build.json (new or empty)")
      ("in", po::value<std::string>(), "continue from a layer file DIR/layer-NNN.h5 of a build")
      ("fuse.melt-fraction", po::value<double>()->default_value(0.5),
       "the melt fraction a particle must have reached to fuse (0.5: T_m; 1: wholly liquid)")
      ("fuse.level", po::value<double>(),
       "capillary levelling of each layer's deposit: a Gaussian of this standard deviation (m; "
       "default half the beam radius; 0: none; thermal/fusion.hpp)")
      ("snapshots", po::value<std::size_t>()->default_value(10),
       "snapshots in each layer's scan file (besides t = 0)")
      ("map.power", po::value<std::string>(),
       "process map: laser powers, W, comma-separated; with map.speed builds --layers layers at "
       "each point and judges it (docs/build.md \"Process maps\")")
      ("map.speed", po::value<std::string>(), "process map: scan speeds, m/s, comma-separated")
      ("map.hatch", po::value<std::string>(),
       "process map: hatch spacings, m, comma-separated (default: the scan scene's scan.hatch)")
      ("pictures", po::value<bool>()->default_value(true),
       "draw each layer's pictures as PNGs: the particles by state, the lack-of-fusion map, the "
       "solid's height (docs/build.md \"Pictures\"; without matplotlib: one warning, no pictures)");
}

namespace {

// A scene path as given, or beside the build scene when it is relative and not found here.
std::string beside_config(const po::variables_map& vm, const char* option) {
  const std::string path = required<std::string>(vm, option);
  if (fs::path(path).is_absolute() || fs::exists(path) || !vm.count("config")) return path;
  const fs::path there = fs::path(vm["config"].as<std::string>()).parent_path() / path;
  return fs::exists(there) ? there.string() : path;
}

// The options of a stage (deposit or sinter) from its scene file and the extra arguments, parsed
// as that program parses them; errors name the stage's option and file.
po::variables_map parse_stage(const char* option, const char* program,
                              const std::function<void(po::options_description&)>& add,
                              const std::string& scene, const std::string& extra) {
  std::vector<std::string> args{program, "--config", scene};
  std::istringstream words(extra);
  for (std::string w; words >> w;) args.push_back(w);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  po::options_description desc;
  add(desc);
  po::variables_map vm;
  try {
    if (!parse_options(program, "", desc, {}, static_cast<int>(argv.size()), argv.data(), vm))
      throw InputError("asks for help, a version or the config (accepted: scene options only)");
  } catch (const std::exception& e) {
    throw InputError(fmt::format("--{}: {}: {}", option, scene, e.what()));
  }
  return vm;
}

// The stage options the build sets itself (its files, seed, layers, fusion, output, threads):
// given in --spread-args or --sinter-args they would be silently overridden, so they are refused.
struct OwnedOptions {
  const char* extra;               // the build option that carries the stage's arguments
  std::vector<std::string> names;  // the stage's options the build owns
  const char* instead;             // what to use instead
};
const OwnedOptions kSpreadOwned{
    "spread-args",
    {"in", "out", "seed", "layers", "trajectory", "export-deck", "every", "tool-forces",
     "tool-forces-every", "json", "threads", "progress", "config", "print-config"},
    "build's own --in, --out, --seed, --layers, --threads and --progress"};
const OwnedOptions kSinterOwned{
    "sinter-args",
    {"bed", "out", "explain", "fuse", "fuse.melt-fraction", "fuse.level", "fused-bed", "snapshots", "scan.layer",
     "json", "threads", "progress", "config", "print-config"},
    "build's own --out, --fuse.melt-fraction, --fuse.level, --snapshots, --threads and --progress"};

void refuse_owned(const OwnedOptions& owned, const std::string& extra) {
  std::istringstream words(extra);
  for (std::string w; words >> w;) {
    if (w.rfind("--", 0) != 0) continue;
    const std::string name = w.substr(2, w.find('=') - 2);  // --name or --name=value
    if (std::find(owned.names.begin(), owned.names.end(), name) == owned.names.end()) continue;
    throw InputError(fmt::format("--{}: '--{}' is set by the build itself (accepted: the stage's "
                                 "scene options; use the {})",
                                 owned.extra, name, owned.instead));
  }
}

// --out: a new folder (its parent must exist) or an empty one, so that no earlier build's
// files are replaced; the temporaries a killed build left there do not count (they are removed).
// Returns the folder as a path without a trailing separator.
std::string prepare_out(const std::string& out) {
  if (out.empty()) throw InputError("--out: empty (accepted: a new or empty folder)");
  fs::path dir = fs::path(out).lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();  // "run/" is the folder "run"
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir))
      throw InputError(fmt::format("--out: '{}' is a file (accepted: a new or empty folder)", out));
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
      throw InputError(fmt::format("--out: '{}' is not writable (accepted: a new or empty folder "
                                   "that can be written)", out));
    bed::remove_stale_temp_files_in(dir.string());
    if (!fs::is_empty(dir, ec))
      throw InputError(fmt::format("--out: '{}' is not empty (accepted: a new or empty folder, so "
                                   "that no earlier build's files are replaced)",
                                   out));
    return dir.string();
  }
  const fs::path parent = dir.has_parent_path() ? dir.parent_path() : ".";
  if (!fs::is_directory(parent, ec))
    throw InputError(fmt::format("--out: the folder '{}' for '{}' does not exist (accepted: a "
                                 "folder whose parent exists)",
                                 parent.string(), out));
  check_paths({}, {{"--out", dir.string()}});  // a writable parent, a name that fits
  return dir.string();
}

// The scan stage's options: its scene and --sinter-args, then `more` (a map point's power and
// speed), parsed as sinter parses them, and the plan's scan made from them on `box`'s plate.
void parse_scan(Build& b, const bed::Domain& box, const std::string& more) {
  b.scan_options = th::SinterScene{};
  const auto scan_options = [&b](po::options_description& d) {
    add_sinter_options(d, b.scan_options);
  };
  b.svm = parse_stage("sinter", "sinter", scan_options, b.sinter_scene, b.sinter_args + " " + more);
  bed::Bed plate;
  plate.domain = box;
  const std::size_t layer0 = b.svm["scan.layer"].as<std::size_t>();
  b.plan.scan = sinter_scene(b.svm, b.scan_options, plate, layer0);
  b.plan.hatch = scan_hatch(b.svm, b.plan.scan, plate, layer0);
  b.plan.scan_scene_text = scene_text(b.svm);
  b.plan.table = th::read_material_table(b.plan.scan.material_table);
}

// The fusion policy of the build's options.
process::FusionPolicy fusion_policy(const po::variables_map& vm) {
  process::FusionPolicy f;
  f.melt_fraction = vm["fuse.melt-fraction"].as<double>();
  if (!(f.melt_fraction > 0 && f.melt_fraction <= 1))
    throw InputError(fmt::format("--fuse.melt-fraction: {:f} (accepted: 0 < f <= 1; 0.5 fuses what "
                                 "reached T_m, 1 what was wholly liquid)",
                                 f.melt_fraction));
  if (vm.count("fuse.level")) {
    f.level = vm["fuse.level"].as<double>();
    if (!(f.level >= 0))
      throw InputError(fmt::format("--fuse.level: {:f} (accepted: a length >= 0 m)", f.level));
  }
  return f;
}

// The spread stage's part of the plan: deposit's scene and recoater, the supply's finest
// particle, the spread beds' labels and the engine.
void plan_spread(Build& b, const po::variables_map& vm, std::uint64_t seed, int argc, char** argv) {
  process::BuildPlan& p = b.plan;
  p.scene = deposit_scene(b.dvm, b.spread_options.scene);
  p.spread = spread_settings(b.dvm, b.spread_options.spread, seed);
  p.spread.layers = 1;
  p.finest_diameter = 2 * bed::Psd::parse(b.dvm["psd"].as<std::string>(), "--psd").min_radius();
  bed::Bed labels;
  set_spread_provenance(labels, b.dvm, p.scene, "build", argc, argv);
  p.spread_provenance = labels.provenance;
  // liggghts and mpirun are found before layer 1
  if (auto engine = spread_engine(vm, b.dvm, seed))
    p.engine = [engine = *engine](bed::Bed& bed, const dem::Scene& scene,
                                  const dem::SpreadSettings& s,
                                  const std::optional<dem::SpreadState>& state,
                                  std::uint64_t layer, const std::string& out) {
      const std::string folder = (fs::path(out) / fmt::format("liggghts-{:03d}", layer)).string();
      return liggghts_spread_layer(engine, bed, scene, s, state, layer, folder);
    };
}

}  // namespace

bool make_out(const std::string& out) {
  std::error_code ec;
  const bool made = fs::create_directories(out, ec);
  if (ec)
    throw InputError(fmt::format("--out: cannot make the folder '{}': {} (accepted: a folder that "
                                 "can be made)", out, ec.message()));
  return made;
}

Build read_build(const po::variables_map& vm, int argc, char** argv) {
  Build b;
  b.plan.out = required<std::string>(vm, "out");
  const auto seed = required<std::uint64_t>(vm, "seed");
  if (vm["layers"].as<std::uint64_t>() < 1) throw InputError("--layers: 0 (accepted: N >= 1)");
  b.plan.fusion = fusion_policy(vm);
  b.plan.snapshots = vm["snapshots"].as<std::size_t>();
  const std::string spread_scene = beside_config(vm, "spread");
  const std::string sinter_scene = beside_config(vm, "sinter");
  check_paths({{"--spread", spread_scene}, {"--sinter", sinter_scene}}, {});
  if (vm.count("in")) check_paths({{"--in", vm["in"].as<std::string>()}}, {});
  b.plan.out = prepare_out(b.plan.out);
  apply_thread_team(vm);

  const auto spread_options = [&b](po::options_description& d) {
    add_deposit_options(d, b.spread_options);
  };
  refuse_owned(kSpreadOwned, vm["spread-args"].as<std::string>());
  refuse_owned(kSinterOwned, vm["sinter-args"].as<std::string>());
  b.dvm = parse_stage("spread", "deposit", spread_options, spread_scene,
                      vm["spread-args"].as<std::string>() + " --seed " + std::to_string(seed));
  if (!spread_requested(b.dvm))
    throw InputError(fmt::format("--spread: {} names no recoater (accepted: a deposit scene with "
                                 "recoater.tool = blade or roller, docs/deposit-spread.md)",
                                 spread_scene));
  b.sinter_scene = sinter_scene;
  b.sinter_args = vm["sinter-args"].as<std::string>();
  plan_spread(b, vm, seed, argc, argv);
  return b;
}

bed::Bed build_input(const po::variables_map& vm, const Build& b, std::optional<dem::SpreadState>& state) {
  if (!vm.count("in")) {
    bed::Bed bed;
    bed.domain = spread_box(b.dvm);
    return bed;
  }
  const std::string in = vm["in"].as<std::string>();
  bed::Bed bed = bed::read_bed_h5(in);
  if (!dem::has_spread_state(in))
    throw InputError(fmt::format("--in: '{}' has no /restart group (accepted: a layer file "
                                 "DIR/layer-NNN.h5 of a build)",
                                 in));
  state = dem::read_spread_state(in, bed);
  bed.domain = spread_box(b.dvm, bed.domain);
  return bed;
}

th::PartRecord check_scan(Build& b, const bed::Bed& bed, const std::optional<dem::SpreadState>& state,
                          th::PartRecord record, const std::string& more) {
  parse_scan(b, bed.domain, more);
  bed::Bed empty;
  empty.domain = bed.domain;
  th::Sinter probe(empty, process::scan_for_layer(b.plan, 1), b.plan.table,
                   state ? state->floor.z : th::TopHeight{});
  if (record.empty()) return th::part_record(probe.grid());
  th::check_part_grid(record, probe.grid());
  return record;
}

BuildStart start_build(const po::variables_map& vm, Build b) {
  BuildStart s;
  s.layers = vm["layers"].as<std::uint64_t>();
  s.bed = build_input(vm, b, s.state);
  s.part = check_scan(b, s.bed, s.state,
                      vm.count("in") ? th::read_part_record(vm["in"].as<std::string>()) : th::PartRecord{});
  s.first = (s.state ? s.state->layers_done : 0) + 1;
  process::check_layers(b.plan, s.bed.domain, s.first, s.layers);
  s.b = std::move(b);
  return s;
}

OutFolderGuard::~OutFolderGuard() {
  std::error_code ignored;
  if (made && fs::is_empty(path, ignored)) fs::remove(path, ignored);
}

}  // namespace powderbed::app
