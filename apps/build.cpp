// build: a part layer after layer (docs/build.md). Each layer: the recoater spreads powder on the
// solid of the layers before (deposit's recoater scene), the laser scans it (sinter's scene, the
// hatch turned by its rotation each layer), what melted fuses into the solid's raised top, the
// plate goes down, and the next layer is spread on that. Thin: the libraries do the physics
// (dem::run_spread, thermal::Sinter, thermal::fuse, thermal::lack_of_fusion); this program
// chains them in-process and writes each layer's files and the report.
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "build_map.hpp"
#include "build_pictures.hpp"
#include "build_scene.hpp"
#include "common/app_main.hpp"
#include "common/options.hpp"
#include "common/progress.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/process/build_layer.hpp"
#include "powderbed/process/build_plan.hpp"
#include "powderbed/process/build_report.hpp"
#include "powderbed/thermal/explain.hpp"
#include "powderbed/thermal/part_porosity.hpp"
#include "powderbed/thermal/solver.hpp"

namespace {

using namespace powderbed;
namespace fs = std::filesystem;
namespace po = app::po;
namespace th = thermal;
using app::Build;
using process::ReportedLayer;

// The progress bar's callbacks for a layer's spread and scan, each a `share` of the whole run
// from `done` on.
process::Progress progress_part(app::ProgressBar& bar, double done, double share) {
  return [&bar, done, share](double f, const std::string& what) { bar.draw(done + share * f, what); };
}

// build.json in b.out: the layers' reports.
std::string write_build_json(const Build& b, const std::vector<ReportedLayer>& reports,
                             const dem::SpreadState& state, std::uint64_t first,
                             std::size_t particles, double wall) {
  return process::write_build_report(reports, {state.layers_done, first, particles, wall, b.plan.out});
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
                "porosity %.2f %% (interior %.2f %%); mass conserved to %.1e; %.0f s spread + %.0f s "
                "scan\n",
                static_cast<unsigned long long>(r.layer), r.scanned_particles, r.density, r.fused,
                100 * r.fused_fraction, r.balled, r.vaporised, 100 * r.lack_of_fusion,
                r.remelt_mean * 1e6, r.remelt_min * 1e6, r.top_min * 1e6, r.top_max * 1e6,
                100 * r.part.fraction(), 100 * r.interior.fraction(), r.mass_error,
                r.spread.wall_time, r.scan_wall);
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
  return app::check_scan(point, box, std::nullopt, {},
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
  p.porosity = last.interior.fraction();
  p.whole_porosity = last.part.fraction();
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
  app::make_out(point.plan.out);
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
  bed::Bed bed = app::build_input(vm, b, none);
  app::check_scan(b, bed, none, {});
  if (!b.plan.hatch)
    throw InputError("map.power: the scan scene scans no hatch (accepted: a sinter scene with "
                     "scan.hatch: a point's energy density P / (v h t) needs h)");
  const auto powers = map_values(vm, "map.power", "powers, W");
  const auto speeds = map_values(vm, "map.speed", "speeds, m/s");
  const auto hatches = vm.count("map.hatch") ? map_values(vm, "map.hatch", "hatch spacings, m")
                                             : std::vector<double>{b.plan.hatch->spacing};
  const auto layers = vm["layers"].as<std::uint64_t>();
  if (layers < 2)
    throw InputError(fmt::format("--layers: {} with a map (accepted: 2 or more; a point is judged by "
                                 "the porosity of its part below the last layer, which a later "
                                 "scan has been over)", layers));
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
  app::OutFolderGuard guard{b.plan.out, app::make_out(b.plan.out)};

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
  app::add_build_options(desc);
  po::variables_map vm;
  if (!app::parse_options("build", app::kBuildUsage, desc, {}, argc, argv, vm)) return 0;
  app::Build b = app::read_build(vm, argc, argv);
  if (vm.count("map.power") || vm.count("map.speed")) return run_map(vm, b);
  app::BuildStart s = app::start_build(vm, std::move(b));
  app::OutFolderGuard guard{s.b.plan.out, app::make_out(s.b.plan.out)};

  app::ProgressBar bar("build", app::progress_interval(vm));
  app::LayerPictures pictures(vm["pictures"].as<bool>());
  std::vector<ReportedLayer> reports;
  const auto started = std::chrono::steady_clock::now();
  for (std::uint64_t layer = s.first; layer < s.first + s.layers; ++layer) {
    const double done = static_cast<double>(layer - s.first) / static_cast<double>(s.layers);
    const double share = 0.5 / static_cast<double>(s.layers);
    reports.push_back({process::build_layer(s.b.plan, s.bed, s.state, s.part, layer,
                                            progress_part(bar, done, share),
                                            progress_part(bar, done + share, share)), {}});
    // Drawn from the layer's files once they are in place: a picture never fails the build.
    reports.back().pictures =
        pictures.draw(process::layer_file(s.b.plan.out, layer, "-scan"), s.b.plan.out, layer);
  }
  bar.finish();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  write_report(vm, s.b, reports, *s.state, s.first, s.bed.n(), wall);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run_app("build", argc, argv, [&] { return run(argc, argv); });
}
