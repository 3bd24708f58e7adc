#include "powderbed/process/build_layer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <vector>

#include "powderbed/bed/io.hpp"
#include "powderbed/process/scanned_layer_density.hpp"
#include "powderbed/thermal/fusion.hpp"
#include "powderbed/thermal/lack_of_fusion.hpp"
#include "powderbed/thermal/run_output.hpp"

namespace powderbed::process {

namespace {

namespace th = thermal;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// What ends the spread with its bottom above the tool's is not in the layer: the blade scraped
// everything there, so it is in flight (one still in the air would lift the next supply out of
// the box). What lies behind the tool's start ran back under it while the heap formed: the next
// layer's tool would start inside it. Both are removed and counted.
void remove_out_of_layer(const BuildPlan& plan, bed::Bed& bed, dem::SpreadState& next,
                         LayerReport& rep) {
  const dem::Recoater& t = plan.spread.tool;
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

// The scan's and the fusion's numbers in the report.
void report_fusion(const th::Sinter& sinter, const th::Fusion& fused, const th::LackOfFusion& lof,
                   const th::PartRecord& part, LayerReport& rep) {
  const th::SubstrateGeometry& g = sinter.grid();
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
  rep.interior = th::interior_porosity(part);
  rep.part_column_area = g.dx * g.dy;
}

// The scan of layer k on the spread bed and its fusion; writes the scan file; returns the powder
// that stays (fusion's keep flags), sets the solid's new top as the next spread's floor and
// fills the report.
std::vector<char> scan_and_fuse(const BuildPlan& plan, const bed::Bed& bed, bed::HeightMap& floor,
                                th::PartRecord& part, std::uint64_t layer,
                                const Progress& progress, LayerReport& rep) {
  const th::SinterScene scene = scan_for_layer(plan, layer);
  th::Sinter sinter(bed, scene, plan.table, floor.z);
  bed::Bed labelled = bed;
  labelled.provenance.stage = "build: scan of layer " + std::to_string(layer);
  labelled.provenance.scene = plan.scan_scene_text;
  th::RunWriter writer(layer_file(plan.out, layer, "-scan"), labelled, sinter, false);
  const auto steps = static_cast<std::uint64_t>(std::ceil(sinter.t_end() / sinter.dt() * (1 - 1e-12)));
  const std::uint64_t every = plan.snapshots > 0 ? std::max<std::uint64_t>(1, steps / plan.snapshots) : 0;
  const std::string what = fmt::format("layer {} scan", layer);
  const auto start = std::chrono::steady_clock::now();
  rep.scan = sinter.run([&](const th::Sinter& s) { writer.snapshot(s); }, every,
                        [&](const th::SinterProgress& p) {
                          if (progress) progress(p.time / p.t_end, what);
                        });
  rep.scan_wall = seconds_since(start);
  const FusionPolicy& f = plan.fusion;
  const th::Fusion fused = th::fuse(bed, sinter, f.melt_fraction, f.capture,
                                    f.level >= 0 ? f.level : 0.5 * scene.spot_radius);
  const th::LackOfFusion lof =
      th::lack_of_fusion(sinter, scanned_half_width(plan), fused.threshold, floor.z);
  writer.fusion(fused);
  writer.lack_of_fusion(lof);
  th::record_layer(part, sinter, fused, lof);
  writer.part(part);
  writer.finish(sinter, rep.scan, {{"lack_of_fusion", lof.fraction()}});
  rep.density = scanned_layer_density(bed, sinter.grid(), floor.z, lof, rep.tool_bottom);
  rep.scanned_particles = bed.n();
  report_fusion(sinter, fused, lof, part, rep);
  // The spread is periodic across y: fuse gives the solid's image row (the scan's plate is
  // periodic there, substrate.periodic = y) row 0's heights, or, on a bounded plate, joins its
  // two edge rows into one seam (their mean; the volume is kept).
  floor = th::top_surface(sinter.grid(), fused.top);
  std::vector<char> keep(bed.n());
  for (std::size_t i = 0; i < bed.n(); ++i) keep[i] = th::stays_in_bed(fused.state[i]) ? 1 : 0;
  return keep;
}

}  // namespace

std::string layer_file(const std::string& out, std::uint64_t layer, const char* suffix) {
  return (std::filesystem::path(out) /
          fmt::format("layer-{:03d}{}.h5", layer, suffix)).string();
}

SpreadLayer spread_layer(const BuildPlan& plan, bed::Bed& bed,
                         const std::optional<dem::SpreadState>& state, std::uint64_t layer,
                         const Progress& progress) {
  SpreadLayer out;
  LayerReport& rep = out.rep;
  rep.layer = layer;
  rep.tool_bottom = tool_bottom(plan, bed.domain, layer);
  const bool on_solid = state && !state->floor.empty();
  rep.clearance = rep.tool_bottom - (on_solid ? state->floor.highest() : bed.domain.lower[2]);
  if (on_solid && rep.clearance <= 0) {
    const std::string message = fmt::format("layer {}: the solid's top stands {:g} um above the "
                                            "recoater's bottom (the tool strikes the part)",
                                            layer, -rep.clearance * 1e6);
    if (plan.warning) plan.warning(message);
    else std::cerr << "build: warning: " << message << '\n';
  }
  dem::SpreadSettings s = plan.spread;
  const std::string what = fmt::format("layer {} spread", layer);
  if (progress) s.progress = [&](double f, double) { progress(f, what); };
  const dem::SpreadSummary spread =
      plan.engine ? plan.engine(bed, plan.scene, s, state, layer, plan.out)
                  : dem::run_spread(bed, plan.scene, s, state ? &*state : nullptr);
  rep.spread = spread.layers.back();
  rep.rebuilds = spread.neighbour_rebuilds;
  out.next = spread.state;
  remove_out_of_layer(plan, bed, out.next, rep);
  out.spread = bed;
  out.spread.provenance = plan.spread_provenance;
  bed::write_bed_h5(out.spread, layer_file(plan.out, layer, "-spread"));
  return out;
}

LayerReport scan_layer(const BuildPlan& plan, bed::Bed& bed, SpreadLayer spread,
                       std::optional<dem::SpreadState>& state, thermal::PartRecord& part,
                       std::uint64_t layer, const Progress& progress) {
  LayerReport rep = std::move(spread.rep);
  dem::SpreadState next = std::move(spread.next);
  const std::vector<char> keep =
      scan_and_fuse(plan, spread.spread, next.floor, part, layer, progress, rep);
  dem::remove_particles(bed, next, keep);
  bed.provenance = plan.spread_provenance;
  bed.provenance.stage = "build: powder after layer " + std::to_string(layer);
  dem::write_spread_bed(layer_file(plan.out, layer, ""), bed, next,
                        [&](bed::H5Output& out) { thermal::write_part_record(out, part); });
  state = next;
  return rep;
}

LayerReport build_layer(const BuildPlan& plan, bed::Bed& bed, std::optional<dem::SpreadState>& state,
                        thermal::PartRecord& part, std::uint64_t layer,
                        const Progress& spread_progress, const Progress& scan_progress) {
  SpreadLayer spread = spread_layer(plan, bed, state, layer, spread_progress);
  return scan_layer(plan, bed, std::move(spread), state, part, layer, scan_progress);
}

}  // namespace powderbed::process
