#include "build_map.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "powderbed/bed/json_units.hpp"

namespace powderbed::app {

namespace {

// Johnson et al. 2019: a pool no wider than 1.5 times its depth is a keyhole's.
constexpr double kKeyholeWidthOverDepth = 1.5;

constexpr bed::UnitEntry kUnits[] = {
    {"wall_time", "s"},          {"power", "W"},
    {"speed", "m/s"},            {"hatch", "m"},
    {"layer", "m"},              {"energy_density", "J/m^3"},
    {"porosity", "1"},           {"lack_of_fusion", "1"},
    {"remelt_depth_mean", "m"},  {"mean_track_width", "m"},
    {"mean_track_depth", "m"},   {"normalised_enthalpy", "1"},
    {"keyhole_threshold", "1"},  {"tang", "1"},
    {"balling_tracks", "1"},     {"tracks", "1"},
    {"layer_density", "1"},      {"points", "1"},
    {"dense_porosity", "1"},     {"whole_porosity", "1"}};

}  // namespace

double MapPoint::tang() const {
  if (!(width > 0 && depth > 0)) return std::numeric_limits<double>::infinity();
  const double h = hatch / width, t = layer / (layer + depth);
  return h * h + t * t;
}

std::vector<std::string> MapPoint::regions() const {
  std::vector<std::string> out;
  if (normalised_enthalpy > keyhole_threshold || (depth > 0 && width / depth <= kKeyholeWidthOverDepth))
    out.emplace_back("keyhole");
  if (porosity >= kDensePorosity) out.emplace_back("lack of fusion");
  if (balling_tracks > 0) out.emplace_back("balling");
  if (out.empty()) out.emplace_back("dense");
  return out;
}

void write_map_json(bed::JsonWriter& j, const std::vector<MapPoint>& points, double wall) {
  j.begin_object()
      .value("points", static_cast<std::uint64_t>(points.size()))
      .value("wall_time", wall)
      .value("dense_porosity", kDensePorosity);
  j.begin_array("map");
  for (const MapPoint& p : points) {
    j.begin_object()
        .value("power", p.power)
        .value("speed", p.speed)
        .value("hatch", p.hatch)
        .value("layer", p.layer)
        .value("energy_density", p.energy_density())
        .value("folder", p.folder)
        .value("porosity", p.porosity)
        .value("whole_porosity", p.whole_porosity)
        .value("lack_of_fusion", p.lack_of_fusion)
        .value("remelt_depth_mean", p.remelt_mean)
        .value("mean_track_width", p.width)
        .value("mean_track_depth", p.depth)
        .value("normalised_enthalpy", p.normalised_enthalpy)
        .value("keyhole_threshold", p.keyhole_threshold)
        .value("tang", p.tang())
        .value("balling_tracks", static_cast<std::uint64_t>(p.balling_tracks))
        .value("tracks", static_cast<std::uint64_t>(p.tracks))
        .value("layer_density", p.layer_density)
        .value("wall_time", p.wall_time);
    j.begin_array("regions");
    for (const std::string& r : p.regions()) j.value("", r);
    j.end_array().end_object();
  }
  j.end_array();
  bed::write_units(j, kUnits);
  j.end_object();
}

}  // namespace powderbed::app
