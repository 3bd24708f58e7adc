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
#include "common/json_units.hpp"
#include "common/options.hpp"
#include "common/progress.hpp"
#include "common/threads.hpp"
#include "deposit_options.hpp"
#include "deposit_spread.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/bed/temp_files.hpp"
#include "powderbed/dem/recoater.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/thermal/explain.hpp"
#include "powderbed/thermal/fusion.hpp"
#include "powderbed/thermal/lack_of_fusion.hpp"
#include "powderbed/thermal/part_porosity.hpp"
#include "powderbed/thermal/run_output.hpp"
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

std::string layer_file(const std::string& out, std::uint64_t layer, const char* suffix) {
  char name[48];
  std::snprintf(name, sizeof name, "layer-%03llu%s.h5", static_cast<unsigned long long>(layer), suffix);
  return (fs::path(out) / name).string();
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

// The solid fraction of the layer the scan met: the particles whose centres lie over the
// scanned columns (each column owns dx dy around its node) and below the tool's bottom, over
// the space between the solid's top and the tool's bottom there.
double scanned_layer_density(const bed::Bed& bed, const th::SubstrateGeometry& g,
                             const th::TopHeight& top, const th::LackOfFusion& lof, double bottom) {
  double space = 0, solid = 0;
  for (std::size_t c = 0; c < lof.map.size(); ++c)
    if (lof.map[c] != th::kNotScanned)
      space += g.dx * g.dy * std::max(0.0, bottom - (top.empty() ? g.z_top : top[c]));
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const auto col = [&](double v, double v0, double d, std::size_t n) {
      return static_cast<std::size_t>(std::clamp(std::lround((v - v0) / d), 0L, static_cast<long>(n - 1)));
    };
    const std::size_t c = col(bed.x[i], g.x0, g.dx, g.nx) + g.nx * col(bed.y[i], g.y0, g.dy, g.ny);
    if (lof.map[c] == th::kNotScanned || bed.z[i] >= bottom) continue;
    solid += bed::sphere_volume(bed.radius[i]);
  }
  return space > 0 ? solid / space : 0.0;
}

struct LayerReport {
  std::uint64_t layer = 0;
  dem::LayerSummary spread;
  std::uint64_t rebuilds = 0;              // the spread's neighbour-list builds
  std::size_t ejected = 0;                 // in flight above the tool's bottom at the end, removed
  std::size_t behind = 0;                  // behind the tool's start at the end, removed
  double tool_bottom = 0, clearance = 0;  // m: the tool's bottom above the plate, and above the solid
  double density = 0;                      // scanned_layer_density
  th::SinterResult scan;
  double scan_wall = 0;
  std::size_t scanned_particles = 0, fused = 0, vaporised = 0, powder_left = 0;
  double fused_fraction = 0;               // of the powder's mass the scan met
  double mass_error = 0, lack_of_fusion = 0, top_min = 0, top_max = 0;  // top: above the plate
  double scanned_area = 0;                 // m^2: the columns the lack-of-fusion map judged
  double remelt_mean = 0, remelt_min = 0;  // m: remelt depth into the solid below (lack_of_fusion.hpp)
  double solid_mass = 0;                   // kg above the plate after the layer
  th::PartPorosity part;                   // the part so far (part_porosity.hpp)
  double part_column_area = 0;             // m^2: dx dy of the part's columns
  std::size_t captured = 0;                // of the fused: powder the grown solid swallowed
  std::size_t balled = 0;                  // melted on solid that did not melt: balls left in the bed
  app::LayerPictureFiles pictures;         // the layer's PNGs in --out (none: --pictures false)
};

void layer_json(bed::JsonWriter& j, const LayerReport& l) {
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
  for (const auto& [kind, file] : l.pictures) j.value(kind, file);
  j.end_object().end_object();
}

// Everything a layer needs that stays from one layer to the next.
struct Build {
  po::variables_map dvm, svm;
  app::DepositOptions spread_options;  // what the spread stage's options of a plain type filled
  th::SinterScene scan_options;        // ... and the scan stage's (app::sinter_scene starts there)
  dem::Scene scene;
  dem::SpreadSettings spread;
  th::MaterialTable table;
  std::string out;
  double melt_fraction = 0.5;
  double level = -1;            // fuse.level, m (< 0: half the beam radius)
  std::size_t snapshots = 10;
  std::size_t scan_layer0 = 0;  // the sinter scene's scan.layer: the first layer's rotation step
  std::string sinter_scene, sinter_args;  // the scan stage's scene and --sinter-args (a map's
                                          // points parse them again with their power and speed)
  std::string command_line;
  std::optional<app::LiggghtsEngine> engine;  // --spread-engine liggghts; none: dem::run_spread
};

// The tool's lowest point above the plate at layer k (the plate has gone down k - 1 layers).
double tool_bottom(const Build& b, const bed::Bed& bed, std::uint64_t layer) {
  return bed.domain.lower[2] + b.spread.tool.gap +
         static_cast<double>(layer - 1) * b.spread.layer_thickness;
}

// Every layer's tool inside the box, checked before layer 1 is spread (the spread checks each
// layer's only when it gets there): the last layer's bottom below the box's top, and no count
// that wraps past the last layer number.
void check_layers(const Build& b, const bed::Bed& bed, std::uint64_t first, std::uint64_t layers) {
  const double top = bed.domain.upper[2];
  const std::uint64_t last = first + layers - 1;
  // A layer (past the first, whose gap is the tool's) thinner than the finest particle the
  // supply holds: the plate would go down by less than any particle it is to take.
  const double finest = 2 * bed::Psd::parse(b.dvm["psd"].as<std::string>(), "--psd").min_radius();
  if (last > 1 && b.spread.layer_thickness < finest) {
    throw InputError(fmt::format(
        "recoater.layer-thickness: {:g} m, thinner than the finest particle of the spread scene's "
        "psd ({:g} m across) (accepted: a layer at least as thick as the finest particle)",
        b.spread.layer_thickness, finest));
  }
  if (last >= first && tool_bottom(b, bed, last) < top) return;
  // The last layer that fits (0: not even the first), by the spread's own test; the estimate
  // from the box's height may be one off in floating point. Layers that do not raise the tool
  // all fit or none does.
  const double t = b.spread.layer_thickness;
  const double room = t > 0 ? (top - bed.domain.lower[2] - b.spread.tool.gap) / t : 0.0;
  auto fit = static_cast<std::uint64_t>(std::clamp(std::ceil(room), 0.0, 1e15));
  if (fit > 0 && !(tool_bottom(b, bed, fit) < top)) --fit;
  if (t > 0 && tool_bottom(b, bed, fit + 1) < top) ++fit;
  throw InputError(fmt::format("--layers: {} from layer {}: the tool rises above the box's top "
                               "after layer {} (accepted: a taller box or at most {} layers)",
                               layers, first, fit, fit >= first ? fit - first + 1 : 0));
}

// The scan of layer k on the spread bed and its fusion; writes the scan file; returns the powder
// that stays (fusion's keep flags), sets the solid's new top as the next spread's floor and
// fills the report.
std::vector<char> scan_and_fuse(const Build& b, const bed::Bed& bed, bed::HeightMap& floor,
                                th::PartRecord& part, std::uint64_t layer, app::ProgressBar& bar,
                                double done, double share, LayerReport& rep) {
  const th::SinterScene scene =
      app::sinter_scene(b.svm, b.scan_options, bed, b.scan_layer0 + layer - 1);
  th::Sinter sinter(bed, scene, b.table, floor.z);
  bed::Bed labelled = bed;
  labelled.provenance.created_by = app::version_string("build");
  labelled.provenance.command_line = b.command_line;
  labelled.provenance.stage = "build: scan of layer " + std::to_string(layer);
  labelled.provenance.scene = app::scene_text(b.svm);
  th::RunWriter writer(layer_file(b.out, layer, "-scan"), labelled, sinter, false);
  const auto steps = static_cast<std::uint64_t>(std::ceil(sinter.t_end() / sinter.dt() * (1 - 1e-12)));
  const std::uint64_t every = b.snapshots > 0 ? std::max<std::uint64_t>(1, steps / b.snapshots) : 0;
  const auto start = std::chrono::steady_clock::now();
  rep.scan = sinter.run([&](const th::Sinter& s) { writer.snapshot(s); }, every,
                        [&](const th::SinterProgress& p) {
                          bar.draw(done + share * p.time / p.t_end,
                                   fmt::format("layer {} scan", layer));
                        });
  rep.scan_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The deposit levelled (by default over half the beam radius: the melt pool spans ~2 w across)
  // before powder the grown solid overlaps by more than 5 % of its radius joins it (fusion.hpp):
  // the Hertz overlap of a resting particle under the scenes' softening is ~2 % of r.
  const double level = b.level >= 0 ? b.level : 0.5 * scene.spot_radius;
  const th::Fusion fused = th::fuse(bed, sinter, b.melt_fraction, 0.05, level);
  const double half_width = app::hatch_requested(b.svm) ? 0.5 * b.svm["scan.hatch"].as<double>()
                                                        : scene.spot_radius;
  const th::LackOfFusion lof = th::lack_of_fusion(sinter, half_width, fused.threshold, floor.z);
  writer.fusion(fused);
  writer.lack_of_fusion(lof);
  th::record_layer(part, sinter, fused, lof);
  writer.part(part);
  writer.finish(sinter, rep.scan, {{"lack_of_fusion", lof.fraction()}});
  const th::SubstrateGeometry& g = sinter.grid();
  rep.density = scanned_layer_density(bed, g, floor.z, lof, rep.tool_bottom);
  rep.scanned_particles = bed.n();
  rep.fused = fused.fused;
  rep.captured = fused.captured;
  rep.balled = fused.balled;
  rep.vaporised = fused.vaporised;
  rep.powder_left = fused.powder.n();
  rep.fused_fraction = fused.fused_fraction();
  rep.mass_error = fused.mass_error();
  rep.lack_of_fusion = lof.fraction();
  rep.remelt_mean = lof.mean_remelt();
  rep.remelt_min = lof.min_remelt();
  rep.scanned_area = static_cast<double>(lof.scanned) * g.dx * g.dy;
  const auto [low, high] = std::minmax_element(fused.top.begin(), fused.top.end());
  rep.top_min = *low - g.z_top;
  rep.top_max = *high - g.z_top;
  rep.solid_mass = fused.solid_mass_after;
  rep.part = th::part_porosity(part);
  rep.part_column_area = g.dx * g.dy;
  // The spread is periodic across y, the thermal grid is not: fuse joins the solid's two edge
  // rows into one seam (their mean; the volume is kept) before it captures what the seam buries.
  floor = th::top_surface(g, fused.top);
  std::vector<char> keep(bed.n());
  for (std::size_t i = 0; i < bed.n(); ++i) keep[i] = th::stays_in_bed(fused.state[i]) ? 1 : 0;
  return keep;
}

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
// speed), parsed as sinter parses them into b.svm and b.scan_options.
void parse_scan(Build& b, const std::string& more) {
  b.scan_options = th::SinterScene{};
  const auto scan_options = [&b](po::options_description& d) {
    app::add_sinter_options(d, b.scan_options);
  };
  b.svm = parse_stage("sinter", "sinter", scan_options, b.sinter_scene, b.sinter_args + " " + more);
  b.scan_layer0 = b.svm["scan.layer"].as<std::size_t>();
}

// The build's own options, the stage scenes parsed by their programs' options, the checks made
// before anything is written.
Build read_build(const po::variables_map& vm, int argc, char** argv) {
  Build b;
  b.out = app::required<std::string>(vm, "out");
  const auto seed = app::required<std::uint64_t>(vm, "seed");
  if (vm["layers"].as<std::uint64_t>() < 1) throw InputError("--layers: 0 (accepted: N >= 1)");
  b.melt_fraction = vm["fuse.melt-fraction"].as<double>();
  if (!(b.melt_fraction > 0 && b.melt_fraction <= 1))
    throw InputError(fmt::format("--fuse.melt-fraction: {:f} (accepted: 0 < f <= 1; 0.5 fuses what "
                                 "reached T_m, 1 what was wholly liquid)",
                                 b.melt_fraction));
  b.snapshots = vm["snapshots"].as<std::size_t>();
  if (vm.count("fuse.level")) {
    b.level = vm["fuse.level"].as<double>();
    if (!(b.level >= 0))
      throw InputError(fmt::format("--fuse.level: {:f} (accepted: a length >= 0 m)", b.level));
  }
  b.command_line = app::command_line(argc, argv);
  const std::string spread_scene = beside_config(vm, "spread");
  const std::string sinter_scene = beside_config(vm, "sinter");
  app::check_paths({{"--spread", spread_scene}, {"--sinter", sinter_scene}}, {});
  if (vm.count("in")) app::check_paths({{"--in", vm["in"].as<std::string>()}}, {});
  b.out = prepare_out(b.out);
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
  parse_scan(b, "");
  b.scene = app::deposit_scene(b.dvm, b.spread_options.scene);
  b.spread = app::spread_settings(b.dvm, b.spread_options.spread, seed);
  b.spread.layers = 1;
  b.engine = app::spread_engine(vm, b.dvm, seed);  // liggghts and mpirun found before layer 1
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

// The scan stage checked before any layer is spread: its options, its path on the plate and its
// grid under the solid (a bed without particles: the scene and the grid alone). Returns the
// part's record to go on from: `record` (from --in) checked against that grid, or a new one on
// it when `record` is empty.
th::PartRecord check_scan(Build& b, const bed::Bed& bed, const std::optional<dem::SpreadState>& state,
                          th::PartRecord record) {
  b.table = th::read_material_table(app::sinter_scene(b.svm, b.scan_options, bed).material_table);
  bed::Bed empty;
  empty.domain = bed.domain;
  th::Sinter probe(empty, app::sinter_scene(b.svm, b.scan_options, empty, b.scan_layer0), b.table,
                   state ? state->floor.z : th::TopHeight{});
  if (record.empty()) return th::part_record(probe.grid());
  th::check_part_grid(record, probe.grid());
  return record;
}

// What ends the spread with its bottom above the tool's is not in the layer: the blade scraped
// everything there, so it is in flight (one still in the air would lift the next supply out of
// the box). What lies behind the tool's start ran back under it while the heap formed: the next
// layer's tool would start inside it. Both are removed and counted.
void remove_out_of_layer(const Build& b, bed::Bed& bed, dem::SpreadState& next, LayerReport& rep) {
  const dem::Recoater& t = b.spread.tool;
  const double start = t.start + (t.shape == dem::ToolShape::blade ? 0.5 * t.thickness : t.radius);
  std::vector<char> keep(bed.n(), 1);
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const bool flying = bed.z[i] - bed.radius[i] > rep.tool_bottom;
    rep.ejected += flying ? 1 : 0;
    rep.behind += !flying && bed.x[i] < start ? 1 : 0;
    keep[i] = flying || bed.x[i] < start ? 0 : 1;
  }
  dem::remove_particles(bed, next, keep);
}

// A layer spread on the solid (the state's floor): the bed the scan meets and the spread's state
// after it, with the report's spread part; written as layer-NNN-spread.h5. `bed` becomes the
// spread bed (what ended out of the layer removed).
struct SpreadLayer {
  bed::Bed spread;        // with the spread's provenance
  dem::SpreadState next;
  LayerReport rep;
};

SpreadLayer spread_layer(const Build& b, bed::Bed& bed, const std::optional<dem::SpreadState>& state,
                         std::uint64_t layer, app::ProgressBar& bar, double done, double share,
                         int argc, char** argv) {
  SpreadLayer out;
  LayerReport& rep = out.rep;
  rep.layer = layer;
  rep.tool_bottom = tool_bottom(b, bed, layer);
  const double solid_top = state && !state->floor.empty() ? state->floor.highest() : bed.domain.lower[2];
  rep.clearance = rep.tool_bottom - solid_top;
  if (state && !state->floor.empty() && rep.clearance <= 0)
    std::cerr << fmt::format("build: warning: layer {}: the solid's top stands {:g} um above the "
                             "recoater's bottom (the tool strikes the part)\n",
                             layer, -rep.clearance * 1e6);
  dem::SpreadSettings s = b.spread;
  s.progress = [&](double f, double) {
    bar.draw(done + share * f, fmt::format("layer {} spread", layer));
  };
  const dem::SpreadSummary spread =
      b.engine ? app::liggghts_spread_layer(*b.engine, bed, b.scene, s, state, layer,
                                            (fs::path(b.out) / fmt::format("liggghts-{:03d}", layer)).string())
               : dem::run_spread(bed, b.scene, s, state ? &*state : nullptr);
  rep.spread = spread.layers.back();
  rep.rebuilds = spread.neighbour_rebuilds;
  out.next = spread.state;
  remove_out_of_layer(b, bed, out.next, rep);
  out.spread = bed;
  app::set_spread_provenance(out.spread, b.dvm, b.scene, "build", argc, argv);
  bed::write_bed_h5(out.spread, layer_file(b.out, layer, "-spread"));
  return out;
}

// The scan of a spread layer, its fusion and what stays: the fused solid becomes the floor of
// the next layer's spread, the rest stays powder (`bed`, the spread bed); writes the layer's scan
// file and its layer file (with the part's record); the state becomes the next layer's.
LayerReport scan_layer(const Build& b, bed::Bed& bed, SpreadLayer spread,
                       std::optional<dem::SpreadState>& state, th::PartRecord& part,
                       std::uint64_t layer, app::ProgressBar& bar, double done, double share,
                       int argc, char** argv) {
  LayerReport rep = std::move(spread.rep);
  dem::SpreadState next = std::move(spread.next);
  const std::vector<char> keep =
      scan_and_fuse(b, spread.spread, next.floor, part, layer, bar, done, share, rep);
  dem::remove_particles(bed, next, keep);
  app::set_spread_provenance(bed, b.dvm, b.scene, "build", argc, argv);
  bed.provenance.stage = "build: powder after layer " + std::to_string(layer);
  dem::write_spread_bed(layer_file(b.out, layer, ""), bed, next,
                        [&](bed::H5Output& out) { th::write_part_record(out, part); });
  state = next;
  return rep;
}

// One layer: spread, scan, fuse, write the layer's files.
LayerReport build_layer(const Build& b, bed::Bed& bed, std::optional<dem::SpreadState>& state,
                        th::PartRecord& part, std::uint64_t layer, app::ProgressBar& bar,
                        double done, double share, int argc, char** argv) {
  SpreadLayer spread = spread_layer(b, bed, state, layer, bar, done, share, argc, argv);
  return scan_layer(b, bed, std::move(spread), state, part, layer, bar, done + share, share, argc, argv);
}

// The units of build.json's numbers (common/json_units).
constexpr app::UnitEntry kUnits[] = {
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
std::string write_build_json(const Build& b, const std::vector<LayerReport>& reports,
                             const dem::SpreadState& state, std::uint64_t first,
                             std::size_t particles, double wall) {
  bed::JsonWriter j;
  j.begin_object()
      .value("layers_done", state.layers_done)
      .value("first_layer", first)
      .value("particles", static_cast<std::uint64_t>(particles))
      .value("wall_time", wall);
  j.begin_array("layers");
  for (const auto& r : reports) layer_json(j, r);
  j.end_array();
  j.value("out", b.out);
  app::write_units(j, kUnits);
  j.end_object();
  bed::write_text_file((fs::path(b.out) / "build.json").string(), j.str() + "\n");
  return j.str();
}

// build.json, and the summary on stdout (the report itself with --json).
void write_report(const po::variables_map& vm, const Build& b, const std::vector<LayerReport>& reports,
                  const dem::SpreadState& state, std::uint64_t first, std::size_t particles, double wall) {
  const std::string json = write_build_json(b, reports, state, first, particles, wall);
  if (vm.count("json")) {
    std::cout << json << '\n';
    return;
  }
  for (const auto& r : reports)
    std::printf("build: layer %llu: %zu particles spread (density %.3f over the scan), %zu fused "
                "(%.0f %% of the powder's mass), %zu balled, %zu vaporised; lack of fusion %.1f %% of the "
                "scanned area, remelt depth %.1f um mean (%.1f min); solid top %.1f to %.1f um; part "
                "porosity %.2f %%; mass conserved to %.1e; %.0f s spread + %.0f s scan\n",
                static_cast<unsigned long long>(r.layer), r.scanned_particles, r.density, r.fused,
                100 * r.fused_fraction, r.balled, r.vaporised, 100 * r.lack_of_fusion,
                r.remelt_mean * 1e6, r.remelt_min * 1e6, r.top_min * 1e6, r.top_max * 1e6,
                100 * r.part.fraction(), r.mass_error, r.spread.wall_time, r.scan_wall);
  std::printf("build: %zu layer(s) in %.0f s -> %s\n", reports.size(), wall, b.out.c_str());
}

// map.json and map.png in --out, and the summary on stdout (map.json itself with --json).
void write_map(const po::variables_map& vm, const Build& b, const std::vector<app::MapPoint>& map,
               double wall) {
  bed::JsonWriter j;
  app::write_map_json(j, map, wall);
  const std::string json = (fs::path(b.out) / "map.json").string();
  bed::write_text_file(json, j.str() + "\n");
  const std::string png = (fs::path(b.out) / "map.png").string();
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
  std::printf("build: map of %zu point(s) in %.0f s -> %s\n", map.size(), wall, b.out.c_str());
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
  parse_scan(point, fmt::format("--power {} --speed {} --scan.hatch {}", power, speed, hatch));
  point.out = (fs::path(point.out) / fmt::format("point-{:03d}", index)).string();
  return check_scan(point, box, std::nullopt, {});
}

// What the map judges a point by, from its last layer and its part.
app::MapPoint map_point(const Build& point, const bed::Bed& box, const LayerReport& last,
                        double power, double speed, double hatch) {
  app::MapPoint p;
  p.power = power;
  p.speed = speed;
  p.hatch = hatch;
  p.layer = point.spread.layer_thickness;
  p.folder = fs::path(point.out).filename().string();
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
  const th::SinterScene scene = app::sinter_scene(point.svm, point.scan_options, empty, point.scan_layer0);
  const th::Sinter probe(empty, scene, point.table);
  const th::KingRegime king = th::king_regime(scene, probe.material());
  p.normalised_enthalpy = king.normalised_enthalpy;
  p.keyhole_threshold = king.keyhole_threshold;
  return p;
}

// build --map.power ... --map.speed ...: the first layer is spread once (it does not depend on
// the laser), and every point scans it and builds its further layers in its own folder; map.json
// and map.png in --out.
int run_map(const po::variables_map& vm, Build& b, int argc, char** argv) {
  if (!vm.count("map.power") || !vm.count("map.speed"))
    throw InputError("map.power / map.speed: one given without the other (accepted: both, "
                     "comma-separated lists)");
  if (vm.count("in"))
    throw InputError("--in: not with a map (accepted: a map builds every point from the empty box)");
  if (!app::hatch_requested(b.svm))
    throw InputError("map.power: the scan scene scans no hatch (accepted: a sinter scene with "
                     "scan.hatch: a point's energy density P / (v h t) needs h)");
  const auto powers = map_values(vm, "map.power", "powers, W");
  const auto speeds = map_values(vm, "map.speed", "speeds, m/s");
  const auto hatches = vm.count("map.hatch") ? map_values(vm, "map.hatch", "hatch spacings, m")
                                             : std::vector<double>{b.svm["scan.hatch"].as<double>()};
  const auto layers = vm["layers"].as<std::uint64_t>();
  std::optional<dem::SpreadState> none;
  bed::Bed bed = build_input(vm, b, none);
  check_scan(b, bed, none, {});
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
  check_layers(b, bed, 1, layers);
  OutFolderGuard guard{b.out, make_out(b.out)};

  app::ProgressBar bar("build", app::progress_interval(vm));
  app::LayerPictures pictures(vm["pictures"].as<bool>());
  const double share = 1.0 / static_cast<double>(1 + points.size() * (2 * layers - 1));
  const auto started = std::chrono::steady_clock::now();
  const SpreadLayer spread = spread_layer(b, bed, none, 1, bar, 0, share, argc, argv);
  std::vector<app::MapPoint> map;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Build& point = points[k];
    const auto point_started = std::chrono::steady_clock::now();
    make_out(point.out);
    bed::Bed powder = bed;
    std::optional<dem::SpreadState> state;
    double done = share * static_cast<double>(1 + k * (2 * layers - 1));
    std::vector<LayerReport> reports{scan_layer(point, powder, spread, state, parts[k], 1, bar, done, share, argc, argv)};
    done += share;
    for (std::uint64_t layer = 2; layer <= layers; ++layer, done += 2 * share)
      reports.push_back(build_layer(point, powder, state, parts[k], layer, bar, done, share, argc, argv));
    for (std::uint64_t layer = 1; layer <= layers; ++layer)
      reports[layer - 1].pictures = pictures.draw(layer_file(point.out, layer, "-scan"), point.out, layer);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - point_started).count();
    write_build_json(point, reports, *state, 1, powder.n(), wall);
    const auto [power, speed, hatch] = settings[k];
    map.push_back(map_point(point, bed, reports.back(), power, speed, hatch));
    map.back().wall_time = wall;
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
  if (vm.count("map.power") || vm.count("map.speed")) return run_map(vm, b, argc, argv);
  const auto layers = vm["layers"].as<std::uint64_t>();
  std::optional<dem::SpreadState> state;
  bed::Bed bed = build_input(vm, b, state);
  th::PartRecord part = check_scan(
      b, bed, state, vm.count("in") ? th::read_part_record(vm["in"].as<std::string>()) : th::PartRecord{});
  const std::uint64_t first = (state ? state->layers_done : 0) + 1;
  check_layers(b, bed, first, layers);
  OutFolderGuard guard{b.out, make_out(b.out)};

  app::ProgressBar bar("build", app::progress_interval(vm));
  app::LayerPictures pictures(vm["pictures"].as<bool>());
  std::vector<LayerReport> reports;
  const auto started = std::chrono::steady_clock::now();
  for (std::uint64_t layer = first; layer < first + layers; ++layer) {
    const double done = static_cast<double>(layer - first) / static_cast<double>(layers);
    const double share = 0.5 / static_cast<double>(layers);
    reports.push_back(build_layer(b, bed, state, part, layer, bar, done, share, argc, argv));
    // Drawn from the layer's files once they are in place: a picture never fails the build.
    reports.back().pictures = pictures.draw(layer_file(b.out, layer, "-scan"), b.out, layer);
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
