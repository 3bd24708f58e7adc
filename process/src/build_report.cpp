#include "powderbed/process/build_report.hpp"

#include <filesystem>

#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/json_units.hpp"

namespace powderbed::process {

namespace {

// The units of build.json's numbers (bed/json_units.hpp).
constexpr bed::UnitEntry kUnits[] = {
    {"layers_done", "1"}, {"first_layer", "1"}, {"particles", "1"}, {"wall_time", "s"},
    {"layer", "1"}, {"particles_spread", "1"}, {"supplied", "1"}, {"overflow", "1"},
    {"under_platform", "1"}, {"tool_bottom", "m"}, {"recoater_clearance", "m"}, {"layer_density", "1"},
    {"spread_steps", "1"}, {"neighbour_rebuilds", "1"}, {"ejected", "1"}, {"behind_start", "1"},
    {"spread_settle_time", "s"}, {"spread_asleep", "1"}, {"sleep_changes", "1"},
    {"spread_wall_time", "s"}, {"tracks", "1"}, {"mean_track_width", "m"},
    {"mean_track_depth", "m"}, {"max_temperature", "K"}, {"absorptance", "1"},
    {"depression_depth", "m"}, {"evaporated_mass", "kg"}, {"energy_balance_error", "1"},
    {"scan_wall_time", "s"}, {"fused", "1"}, {"vaporised", "1"}, {"powder_left", "1"},
    {"captured", "1"}, {"balled", "1"}, {"fused_fraction", "1"}, {"lack_of_fusion", "1"},
    {"remelt_depth_mean", "m"}, {"remelt_depth_min", "m"}, {"scanned_area", "m^2"},
    {"mass_error", "1"}, {"solid_top_min", "m"}, {"solid_top_max", "m"}, {"solid_mass", "kg"},
    {"part_porosity", "1"}, {"interior_porosity", "1"}, {"part_core_area", "m^2"}};

}  // namespace

void write_layer_json(bed::JsonWriter& j, const LayerReport& l, const LayerPictureFiles& pictures) {
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
      .value("under_platform", static_cast<std::uint64_t>(l.spread.under_platform))
      .value("tool_bottom", l.tool_bottom)
      .value("recoater_clearance", l.clearance)
      .value("layer_density", l.density)
      .value("spread_steps", l.spread.steps)
      .value("neighbour_rebuilds", l.rebuilds)
      .value("ejected", static_cast<std::uint64_t>(l.ejected))
      .value("behind_start", static_cast<std::uint64_t>(l.behind))
      .value("spread_settle_time", l.spread.settle_time)
      .value("spread_at_rest", l.spread.at_rest)
      .value("spread_asleep", l.spread.asleep)
      .value("sleep_changes", l.spread.sleep_changes)
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
      .value("interior_porosity", l.interior.fraction())
      .value("part_core_area", static_cast<double>(l.part.core_columns) * l.part_column_area);
  j.begin_object("pictures");
  for (const auto& [kind, file] : pictures) j.value(kind, file);
  j.end_object().end_object();
}

std::string build_report_json(const std::vector<ReportedLayer>& layers, const BuildTotals& totals) {
  bed::JsonWriter j;
  j.begin_object()
      .value("layers_done", totals.layers_done)
      .value("first_layer", totals.first_layer)
      .value("particles", static_cast<std::uint64_t>(totals.particles))
      .value("wall_time", totals.wall_time);
  j.begin_array("layers");
  for (const auto& r : layers) write_layer_json(j, r.report, r.pictures);
  j.end_array();
  j.value("out", totals.out);
  bed::write_units(j, kUnits);
  j.end_object();
  return j.str();
}

std::string write_build_report(const std::vector<ReportedLayer>& layers, const BuildTotals& totals) {
  const std::string json = build_report_json(layers, totals);
  bed::write_text_file((std::filesystem::path(totals.out) / "build.json").string(), json + "\n");
  return json;
}

}  // namespace powderbed::process
