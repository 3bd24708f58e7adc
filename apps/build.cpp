// build: a part layer after layer (docs/build.md). Each layer: the recoater spreads powder on the
// solid of the layers before (deposit's recoater scene), the laser scans it (sinter's scene, the
// hatch turned by its rotation each layer), what melted fuses into the solid's raised top, the
// plate goes down, and the next layer is spread on that. Thin: the libraries do the physics
// (dem::run_spread, thermal::Sinter, thermal::fuse, thermal::lack_of_fusion); this program
// chains them in-process and writes each layer's files and the report.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <unistd.h>

#include "build_map.hpp"
#include "build_pictures.hpp"
#include "common/app_main.hpp"
#include "powderbed/bed/json_units.hpp"
#include "common/options.hpp"
#include "common/progress.hpp"
#include "common/threads.hpp"
#include "deposit_options.hpp"
#include "deposit_spread.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/temp_files.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/process/build_layer.hpp"
#include "powderbed/process/build_plan.hpp"
#include "powderbed/thermal/explain.hpp"
#include "powderbed/thermal/part_porosity.hpp"
#include "powderbed/thermal/solver.hpp"
#include "sinter_options.hpp"
#include "spread_engine_liggghts.hpp"

namespace {

using namespace powderbed;
namespace fs = std::filesystem;
namespace po = app::po;
namespace th = thermal;

const char* const kUsage =
    "build --config BUILD.ini | --spread SPREAD.ini --sinter SINTER.ini --seed S --out DIR "
    "[--layers N] [--in DIR/layer-NNN.h5] [--spread-args \"...\"] [--sinter-args \"...\"] "
    "[--fuse.melt-fraction F] [--snapshots K] [--pictures false] [--spread-engine liggghts [--mpi N]] "
    "[--map.power P1,P2,... --map.speed V1,V2,... [--map.hatch H1,...]] [--json]";

void add_options(po::options_description& desc) {
  app::add_common_options(desc);
  app::add_threads_option(desc);
  app::add_progress_option(desc);
  app::add_spread_engine_options(desc);
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

// A scene path as given, or beside the build scene when it is relative and not found here.
std::string beside_config(const po::variables_map& vm, const char* option) {
  const std::string path = app::required<std::string>(vm, option);
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
    if (!app::parse_options(program, "", desc, {}, static_cast<int>(argv.size()), argv.data(), vm))
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
    {"bed", "out", "explain", "fuse", "fuse.melt-fraction", "fused-bed", "snapshots", "scan.layer",
     "json", "threads", "progress", "config", "print-config"},
    "build's own --out, --fuse.melt-fraction, --snapshots, --threads and --progress"};

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
  app::check_paths({}, {{"--out", dir.string()}});  // a writable parent, a name that fits
  return dir.string();
}

// Makes the --out folder; one line naming it when the file system refuses.
bool make_out(const std::string& out) {
  std::error_code ec;
  const bool made = fs::create_directories(out, ec);
  if (ec)
    throw InputError(fmt::format("--out: cannot make the folder '{}': {} (accepted: a folder that "
                                 "can be made)", out, ec.message()));
  return made;
}

// A layer's object in build.json.
void layer_json(bed::JsonWriter& j, const process::LayerReport& l,
                const app::LayerPictureFiles& pictures) {
  double width = 0, depth = 0;
  for (const auto& t : l.scan.tracks) {
    width += t.pool.width / static_cast<double>(l.scan.tracks.size());
    depth += t.pool.depth / static_cast<double>(l.scan.tracks.size());
  }
  j.begin_object()
      .value("layer", l.layer)
      .value("particles_spread", static_cast<std::uint64_t>(l.scanned_particles))
      .value("supplied", static_cast<std::uint64_t>(l.spread.supplied))
      .value("overflow", static_cast<std::uint64_t>(l.spread.overflow))
      .value("tool_bottom", l.tool_bottom)
      .value("recoater_clearance", l.clearance)
      .value("layer_density", l.density)
      .value("spread_steps", l.spread.steps)
      .value("neighbour_rebuilds", l.rebuilds)
      .value("ejected", static_cast<std::uint64_t>(l.ejected))
      .value("behind_start", static_cast<std::uint64_t>(l.behind))
      .value("spread_wall_time", l.spread.wall_time)
      .value("tracks", static_cast<std::uint64_t>(l.scan.tracks.size()))
      .value("mean_track_width", width)
      .value("mean_track_depth", depth)
      .value("max_temperature", l.scan.max_temperature)
      .value("absorptance", l.scan.absorptance)
      .value("depression_depth", l.scan.depression_depth)
      .value("evaporated_mass", l.scan.evaporated_mass)
      .value("energy_balance_error", l.scan.energy.relative_error())
      .value("scan_wall_time", l.scan_wall)
      .value("fused", static_cast<std::uint64_t>(l.fused))
      .value("vaporised", static_cast<std::uint64_t>(l.vaporised))
      .value("powder_left", static_cast<std::uint64_t>(l.powder_left))
      .value("captured", static_cast<std::uint64_t>(l.captured))
      .value("balled", static_cast<std::uint64_t>(l.balled))
      .value("fused_fraction", l.fused_fraction)
      .value("lack_of_fusion", l.lack_of_fusion)
      .value("remelt_depth_mean", l.remelt_mean)
      .value("remelt_depth_min", l.remelt_min)
      .value("scanned_area", l.scanned_area)
      .value("mass_error", l.mass_error)
      .value("solid_top_min", l.top_min)
      .value("solid_top_max", l.top_max)
      .value("solid_mass", l.solid_mass)
      .value("part_porosity", l.part.fraction())
      .value("part_core_area", static_cast<double>(l.part.core_columns) * l.part_column_area);
  j.begin_object("pictures");
  for (const auto& [kind, file] : pictures) j.value(kind, file);
  j.end_object().end_object();
}

// The build's plan and the stage options it was made from: the map's points parse the scan
// stage again with their power, speed and hatch.
struct Build {
  process::BuildPlan plan;
  po::variables_map dvm, svm;
  app::DepositOptions spread_options;  // what the spread stage's options of a plain type filled
  th::SinterScene scan_options;        // ... and the scan stage's (app::sinter_scene starts there)
  std::string sinter_scene, sinter_args;  // the scan stage's scene and --sinter-args
};

// A layer's report and the pictures drawn from its files.
struct ReportedLayer {
  process::LayerReport report;
  app::LayerPictureFiles pictures;
};

// Removes --out again when the build fails before it wrote anything there (it made the folder).
struct OutFolderGuard {
  std::string path;
  bool made = false;
  ~OutFolderGuard() {
    std::error_code ignored;
    if (made && fs::is_empty(path, ignored)) fs::remove(path, ignored);
  }
};

// The scan stage's options: its scene and --sinter-args, then `more` (a map point's power and
// speed), parsed as sinter parses them, and the plan's scan made from them on `box`'s plate.
void parse_scan(Build& b, const bed::Domain& box, const std::string& more) {
  b.scan_options = th::SinterScene{};
  const auto scan_options = [&b](po::options_description& d) {
    app::add_sinter_options(d, b.scan_options);
  };
  b.svm = parse_stage("sinter", "sinter", scan_options, b.sinter_scene, b.sinter_args + " " + more);
  bed::Bed plate;
  plate.domain = box;
  const std::size_t layer0 = b.svm["scan.layer"].as<std::size_t>();
  b.plan.scan = app::sinter_scene(b.svm, b.scan_options, plate, layer0);
  b.plan.hatch = app::scan_hatch(b.svm, b.plan.scan, plate, layer0);
  b.plan.scan_scene_text = app::scene_text(b.svm);
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
  p.scene = app::deposit_scene(b.dvm, b.spread_options.scene);
  p.spread = app::spread_settings(b.dvm, b.spread_options.spread, seed);
  p.spread.layers = 1;
  p.finest_diameter = 2 * bed::Psd::parse(b.dvm["psd"].as<std::string>(), "--psd").min_radius();
  bed::Bed labels;
  app::set_spread_provenance(labels, b.dvm, p.scene, "build", argc, argv);
  p.spread_provenance = labels.provenance;
  // liggghts and mpirun are found before layer 1
  if (auto engine = app::spread_engine(vm, b.dvm, seed))
    p.engine = [engine = *engine](bed::Bed& bed, const dem::Scene& scene,
                                  const dem::SpreadSettings& s,
                                  const std::optional<dem::SpreadState>& state,
                                  std::uint64_t layer, const std::string& out) {
      const std::string folder = (fs::path(out) / fmt::format("liggghts-{:03d}", layer)).string();
      return app::liggghts_spread_layer(engine, bed, scene, s, state, layer, folder);
    };
}

// The build's own options, the stage scenes parsed by their programs' options into the plan, the
// checks made before anything is written.
Build read_build(const po::variables_map& vm, int argc, char** argv) {
  Build b;
  b.plan.out = app::required<std::string>(vm, "out");
  const auto seed = app::required<std::uint64_t>(vm, "seed");
  if (vm["layers"].as<std::uint64_t>() < 1) throw InputError("--layers: 0 (accepted: N >= 1)");
  b.plan.fusion = fusion_policy(vm);
  b.plan.snapshots = vm["snapshots"].as<std::size_t>();
  const std::string spread_scene = beside_config(vm, "spread");
  const std::string sinter_scene = beside_config(vm, "sinter");
  app::check_paths({{"--spread", spread_scene}, {"--sinter", sinter_scene}}, {});
  if (vm.count("in")) app::check_paths({{"--in", vm["in"].as<std::string>()}}, {});
  b.plan.out = prepare_out(b.plan.out);
  app::apply_thread_team(vm);

  const auto spread_options = [&b](po::options_description& d) {
    app::add_deposit_options(d, b.spread_options);
  };
  refuse_owned(kSpreadOwned, vm["spread-args"].as<std::string>());
  refuse_owned(kSinterOwned, vm["sinter-args"].as<std::string>());
  b.dvm = parse_stage("spread", "deposit", spread_options, spread_scene,
                      vm["spread-args"].as<std::string>() + " --seed " + std::to_string(seed));
  if (!app::spread_requested(b.dvm))
    throw InputError(fmt::format("--spread: {} names no recoater (accepted: a deposit scene with "
                                 "recoater.tool = blade or roller, docs/deposit-spread.md)",
                                 spread_scene));
  b.sinter_scene = sinter_scene;
  b.sinter_args = vm["sinter-args"].as<std::string>();
  plan_spread(b, vm, seed, argc, argv);
  return b;
}

// The powder and the spread's state to continue from (--in), or an empty box.
bed::Bed build_input(const po::variables_map& vm, const Build& b, std::optional<dem::SpreadState>& state) {
  if (!vm.count("in")) {
    bed::Bed bed;
    bed.domain = app::spread_box(b.dvm);
    return bed;
  }
  const std::string in = vm["in"].as<std::string>();
  bed::Bed bed = bed::read_bed_h5(in);
  if (!dem::has_spread_state(in))
    throw InputError(fmt::format("--in: '{}' has no /restart group (accepted: a layer file "
                                 "DIR/layer-NNN.h5 of a build)",
                                 in));
  state = dem::read_spread_state(in, bed);
  bed.domain = app::spread_box(b.dvm, bed.domain);
  return bed;
}

// The scan stage parsed and checked on the bed's plate before any layer is spread: its options,
// its path on the plate and its grid under the solid (a bed without particles: the scene and the
// grid alone); `more`: a map point's power, speed and hatch. Returns the part's record to go on
// from: `record` (from --in) checked against that grid, or a new one on it when `record` is
// empty.
th::PartRecord check_scan(Build& b, const bed::Bed& bed, const std::optional<dem::SpreadState>& state,
                          th::PartRecord record, const std::string& more = "") {
  parse_scan(b, bed.domain, more);
  bed::Bed empty;
  empty.domain = bed.domain;
  th::Sinter probe(empty, process::scan_for_layer(b.plan, 1), b.plan.table,
                   state ? state->floor.z : th::TopHeight{});
  if (record.empty()) return th::part_record(probe.grid());
  th::check_part_grid(record, probe.grid());
  return record;
}

// The progress bar's callbacks for a layer's spread and scan, each a `share` of the whole run
// from `done` on.
process::Progress progress_part(app::ProgressBar& bar, double done, double share) {
  return [&bar, done, share](double f, const std::string& what) { bar.draw(done + share * f, what); };
}

// The units of build.json's numbers (common/json_units).
constexpr bed::UnitEntry kUnits[] = {
    {"layers_done", "1"}, {"first_layer", "1"}, {"particles", "1"}, {"wall_time", "s"},
    {"layer", "1"}, {"particles_spread", "1"}, {"supplied", "1"}, {"overflow", "1"},
    {"tool_bottom", "m"}, {"recoater_clearance", "m"}, {"layer_density", "1"},
    {"spread_steps", "1"}, {"neighbour_rebuilds", "1"}, {"ejected", "1"}, {"behind_start", "1"},
    {"spread_wall_time", "s"}, {"tracks", "1"}, {"mean_track_width", "m"},
    {"mean_track_depth", "m"}, {"max_temperature", "K"}, {"absorptance", "1"},
    {"depression_depth", "m"}, {"evaporated_mass", "kg"}, {"energy_balance_error", "1"},
    {"scan_wall_time", "s"}, {"fused", "1"}, {"vaporised", "1"}, {"powder_left", "1"},
    {"captured", "1"}, {"balled", "1"}, {"fused_fraction", "1"}, {"lack_of_fusion", "1"},
    {"remelt_depth_mean", "m"}, {"remelt_depth_min", "m"}, {"scanned_area", "m^2"},
    {"mass_error", "1"}, {"solid_top_min", "m"}, {"solid_top_max", "m"}, {"solid_mass", "kg"},
    {"part_porosity", "1"}, {"part_core_area", "m^2"}};

// build.json in b.out: the layers' reports.
std::string write_build_json(const Build& b, const std::vector<ReportedLayer>& reports,
                             const dem::SpreadState& state, std::uint64_t first,
                             std::size_t particles, double wall) {
  bed::JsonWriter j;
  j.begin_object()
      .value("layers_done", state.layers_done)
      .value("first_layer", first)
      .value("particles", static_cast<std::uint64_t>(particles))
      .value("wall_time", wall);
  j.begin_array("layers");
  for (const auto& r : reports) layer_json(j, r.report, r.pictures);
  j.end_array();
  j.value("out", b.plan.out);
  bed::write_units(j, kUnits);
  j.end_object();
  bed::write_text_file((fs::path(b.plan.out) / "build.json").string(), j.str() + "\n");
  return j.str();
}

// build.json, and the summary on stdout (the report itself with --json).
void write_report(const po::variables_map& vm, const Build& b, const std::vector<ReportedLayer>& reports,
                  const dem::SpreadState& state, std::uint64_t first, std::size_t particles, double wall) {
  const std::string json = write_build_json(b, reports, state, first, particles, wall);
  if (vm.count("json")) {
    std::cout << json << '\n';
    return;
  }
  for (const auto& [r, pictures] : reports)
    std::printf("build: layer %llu: %zu particles spread (density %.3f over the scan), %zu fused "
                "(%.0f %% of the powder's mass), %zu balled, %zu vaporised; lack of fusion %.1f %% of the "
                "scanned area, remelt depth %.1f um mean (%.1f min); solid top %.1f to %.1f um; part "
                "porosity %.2f %%; mass conserved to %.1e; %.0f s spread + %.0f s scan\n",
                static_cast<unsigned long long>(r.layer), r.scanned_particles, r.density, r.fused,
                100 * r.fused_fraction, r.balled, r.vaporised, 100 * r.lack_of_fusion,
                r.remelt_mean * 1e6, r.remelt_min * 1e6, r.top_min * 1e6, r.top_max * 1e6,
                100 * r.part.fraction(), r.mass_error, r.spread.wall_time, r.scan_wall);
  std::printf("build: %zu layer(s) in %.0f s -> %s\n", reports.size(), wall, b.plan.out.c_str());
}

// map.json and map.png in --out, and the summary on stdout (map.json itself with --json).
void write_map(const po::variables_map& vm, const Build& b, const std::vector<app::MapPoint>& map,
               double wall) {
  bed::JsonWriter j;
  app::write_map_json(j, map, wall);
  const std::string json = (fs::path(b.plan.out) / "map.json").string();
  bed::write_text_file(json, j.str() + "\n");
  const std::string png = (fs::path(b.plan.out) / "map.png").string();
  const std::string why = vm["pictures"].as<bool>() ? app::draw_map(json, png) : "";
  if (!why.empty()) std::cerr << "build: warning: no map.png: " << why << '\n';
  if (vm.count("json")) {
    std::cout << j.str() << '\n';
    return;
  }
  for (const app::MapPoint& p : map) {
    std::string regions;
    for (const auto& r : p.regions()) regions += (regions.empty() ? "" : ", ") + r;
    std::printf("build: map %s: %g W, %g m/s, hatch %g um, layer %g um (E = %.0f J/mm^3): porosity "
                "%.2f %%, pools %.0f / %.0f um wide / deep, dH/h_s %.1f (keyhole > %.1f): %s\n",
                p.folder.c_str(), p.power, p.speed, p.hatch * 1e6, p.layer * 1e6,
                p.energy_density() * 1e-9, 100 * p.porosity, p.width * 1e6, p.depth * 1e6,
                p.normalised_enthalpy, p.keyhole_threshold, regions.c_str());
  }
  std::printf("build: map of %zu point(s) in %.0f s -> %s\n", map.size(), wall, b.plan.out.c_str());
}

// The values of a map option: a comma-separated list of numbers > 0.
std::vector<double> map_values(const po::variables_map& vm, const char* option, const char* what) {
  const std::string text = vm[option].as<std::string>();
  std::vector<double> out;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    std::size_t used = 0;
    double v = NAN;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size() || !(v > 0) || !std::isfinite(v))
      throw InputError(fmt::format("--{}: '{}' in '{}' (accepted: a comma-separated list of {} > 0)",
                                   option, item, text, what));
    out.push_back(v);
  }
  if (out.empty())
    throw InputError(fmt::format("--{}: no values (accepted: a comma-separated list of {} > 0)",
                                 option, what));
  return out;
}

// A map's point: the build's options with the point's power, speed and hatch, its folder in
// --out; its scan checked (on the empty box), its part's record returned.
th::PartRecord map_point_build(Build& point, const bed::Bed& box, double power, double speed,
                               double hatch, std::size_t index) {
  point.plan.out = (fs::path(point.plan.out) / fmt::format("point-{:03d}", index)).string();
  return check_scan(point, box, std::nullopt, {},
                    fmt::format("--power {} --speed {} --scan.hatch {}", power, speed, hatch));
}

// What the map judges a point by, from its last layer and its part.
app::MapPoint map_point(const Build& point, const bed::Bed& box, const process::LayerReport& last,
                        double power, double speed, double hatch) {
  app::MapPoint p;
  p.power = power;
  p.speed = speed;
  p.hatch = hatch;
  p.layer = point.plan.spread.layer_thickness;
  p.folder = fs::path(point.plan.out).filename().string();
  p.porosity = last.part.fraction();
  p.lack_of_fusion = last.lack_of_fusion;
  p.remelt_mean = last.remelt_mean;
  p.layer_density = last.density;
  p.tracks = last.scan.tracks.size();
  for (const auto& t : last.scan.tracks) {
    p.width += t.pool.width / static_cast<double>(p.tracks);
    p.depth += t.pool.depth / static_cast<double>(p.tracks);
    p.balling_tracks += t.pool.depth == 0 && t.length > std::numbers::pi * t.pool.width ? 1 : 0;
  }
  bed::Bed empty;
  empty.domain = box.domain;
  const th::SinterScene scene = process::scan_for_layer(point.plan, 1);
  const th::Sinter probe(empty, scene, point.plan.table);
  const th::KingRegime king = th::king_regime(scene, probe.material());
  p.normalised_enthalpy = king.normalised_enthalpy;
  p.keyhole_threshold = king.keyhole_threshold;
  return p;
}

// One map point's layers on the first layer's spread, in its own folder; its build.json written
// with the point's wall time (`wall`, s). Returns the last layer's report.
process::LayerReport map_point_layers(const Build& point, const bed::Bed& box,
                                      const process::SpreadLayer& spread, th::PartRecord& part,
                                      std::uint64_t layers, app::ProgressBar& bar, double done,
                                      double share, app::LayerPictures& pictures, double& wall) {
  const auto started = std::chrono::steady_clock::now();
  make_out(point.plan.out);
  bed::Bed powder = box;
  std::optional<dem::SpreadState> state;
  std::vector<ReportedLayer> reports{
      {process::scan_layer(point.plan, powder, spread, state, part, 1, progress_part(bar, done, share)), {}}};
  done += share;
  for (std::uint64_t layer = 2; layer <= layers; ++layer, done += 2 * share)
    reports.push_back({process::build_layer(point.plan, powder, state, part, layer,
                                            progress_part(bar, done, share),
                                            progress_part(bar, done + share, share)), {}});
  for (std::uint64_t layer = 1; layer <= layers; ++layer)
    reports[layer - 1].pictures =
        pictures.draw(process::layer_file(point.plan.out, layer, "-scan"), point.plan.out, layer);
  wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  write_build_json(point, reports, *state, 1, powder.n(), wall);
  return reports.back().report;
}

// build --map.power ... --map.speed ...: the first layer is spread once (it does not depend on
// the laser), and every point scans it and builds its further layers in its own folder; map.json
// and map.png in --out.
int run_map(const po::variables_map& vm, Build& b) {
  if (!vm.count("map.power") || !vm.count("map.speed"))
    throw InputError("map.power / map.speed: one given without the other (accepted: both, "
                     "comma-separated lists)");
  if (vm.count("in"))
    throw InputError("--in: not with a map (accepted: a map builds every point from the empty box)");
  std::optional<dem::SpreadState> none;
  bed::Bed bed = build_input(vm, b, none);
  check_scan(b, bed, none, {});
  if (!b.plan.hatch)
    throw InputError("map.power: the scan scene scans no hatch (accepted: a sinter scene with "
                     "scan.hatch: a point's energy density P / (v h t) needs h)");
  const auto powers = map_values(vm, "map.power", "powers, W");
  const auto speeds = map_values(vm, "map.speed", "speeds, m/s");
  const auto hatches = vm.count("map.hatch") ? map_values(vm, "map.hatch", "hatch spacings, m")
                                             : std::vector<double>{b.plan.hatch->spacing};
  const auto layers = vm["layers"].as<std::uint64_t>();
  std::vector<Build> points;
  std::vector<th::PartRecord> parts;
  std::vector<std::array<double, 3>> settings;
  for (const double h : hatches)
    for (const double power : powers)
      for (const double speed : speeds) {
        points.push_back(b);
        parts.push_back(map_point_build(points.back(), bed, power, speed, h, points.size()));
        settings.push_back({power, speed, h});
      }
  process::check_layers(b.plan, bed.domain, 1, layers);
  OutFolderGuard guard{b.plan.out, make_out(b.plan.out)};

  app::ProgressBar bar("build", app::progress_interval(vm));
  app::LayerPictures pictures(vm["pictures"].as<bool>());
  const double share = 1.0 / static_cast<double>(1 + points.size() * (2 * layers - 1));
  const auto started = std::chrono::steady_clock::now();
  const process::SpreadLayer spread =
      process::spread_layer(b.plan, bed, none, 1, progress_part(bar, 0, share));
  std::vector<app::MapPoint> map;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double done = share * static_cast<double>(1 + k * (2 * layers - 1));
    double point_wall = 0;
    const process::LayerReport last = map_point_layers(points[k], bed, spread, parts[k], layers,
                                                       bar, done, share, pictures, point_wall);
    const auto [power, speed, hatch] = settings[k];
    map.push_back(map_point(points[k], bed, last, power, speed, hatch));
    map.back().wall_time = point_wall;
  }
  bar.finish();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  write_map(vm, b, map, wall);
  return 0;
}

int run(int argc, char** argv) {
  po::options_description desc("build options (SI units)");
  add_options(desc);
  po::variables_map vm;
  if (!app::parse_options("build", kUsage, desc, {}, argc, argv, vm)) return 0;
  Build b = read_build(vm, argc, argv);
  if (vm.count("map.power") || vm.count("map.speed")) return run_map(vm, b);
  const auto layers = vm["layers"].as<std::uint64_t>();
  std::optional<dem::SpreadState> state;
  bed::Bed bed = build_input(vm, b, state);
  th::PartRecord part = check_scan(
      b, bed, state, vm.count("in") ? th::read_part_record(vm["in"].as<std::string>()) : th::PartRecord{});
  const std::uint64_t first = (state ? state->layers_done : 0) + 1;
  process::check_layers(b.plan, bed.domain, first, layers);
  OutFolderGuard guard{b.plan.out, make_out(b.plan.out)};

  app::ProgressBar bar("build", app::progress_interval(vm));
  app::LayerPictures pictures(vm["pictures"].as<bool>());
  std::vector<ReportedLayer> reports;
  const auto started = std::chrono::steady_clock::now();
  for (std::uint64_t layer = first; layer < first + layers; ++layer) {
    const double done = static_cast<double>(layer - first) / static_cast<double>(layers);
    const double share = 0.5 / static_cast<double>(layers);
    reports.push_back({process::build_layer(b.plan, bed, state, part, layer,
                                            progress_part(bar, done, share),
                                            progress_part(bar, done + share, share)), {}});
    // Drawn from the layer's files once they are in place: a picture never fails the build.
    reports.back().pictures =
        pictures.draw(process::layer_file(b.plan.out, layer, "-scan"), b.plan.out, layer);
  }
  bar.finish();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  write_report(vm, b, reports, *state, first, bed.n(), wall);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run_app("build", argc, argv, [&] { return run(argc, argv); });
}
