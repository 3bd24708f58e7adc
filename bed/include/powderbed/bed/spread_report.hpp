#pragma once
// bedstat --spread (docs/spread-layer.md): the statistics of a spread layer per bed, what each
// takes from the command line and what from the bed's own record of the run that made it.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/stats_layer.hpp"

namespace powderbed::bed {

// The feed a layer's sizes are tested against: another bed's sizes or a PSD.
struct SpreadFeed {
  std::string source;              // the --feed file or the PSD text
  std::vector<double> diameters;   // from --feed (empty for a PSD)
  std::optional<bed::Psd> psd;
};

struct SpreadRequest {
  std::optional<double> plate;   // --plate (m); default: the domain floor
  std::optional<double> gap;     // --gap (m); default: the bed's recoater.gap
  std::optional<std::pair<double, double>> window;  // --window x0,x1 (m); default: the domain
  std::optional<double> raster;  // --raster (m); default: a tenth of the mean radius
  std::size_t segregation_bins = 10;
  std::optional<SpreadFeed> feed;  // --feed BED; default: the bed's recorded PSD, if any
  std::string height_map;          // --height-map FILE.csv ("" = none)
};

struct SpreadReport {
  bed::LayerStats layer;
  std::string gap_source;  // "--gap" or "recoater.gap of the bed"
  std::optional<bed::KsTest> ks;
  std::string feed_source;  // what ks compares against
};

// The value of `key` in a bed's recorded scene ("key = value" lines), if present.
std::optional<std::string> scene_value(const std::string& scene, const std::string& key);

// The layer statistics of one bed (`file` names it in messages); throws InputError for a missing
// gap, a bad window or raster, or a 2D bed.
SpreadReport analyse_spread(const bed::Bed& bed, const std::string& file, const SpreadRequest& req);

// The report as the "spread" object of a bed's JSON entry.
void write_spread_json(bed::JsonWriter& json, const SpreadReport& s);

}  // namespace powderbed::bed
