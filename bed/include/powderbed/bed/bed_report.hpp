#pragma once
// bedstat's statistics of one bed and their JSON entry (README "The programs"): what bedstat
// prints per bed under "beds" and what the Python module's stats(bed) returns, from one code.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/json_units.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/stats.hpp"
#include "powderbed/bed/spread_report.hpp"

namespace powderbed::bed {

struct BedRequest {
  double tolerance = 1e-6;
  std::optional<std::pair<double, double>> layer;  // z0, z1 (m)
  std::optional<bed::Psd> psd;
  std::size_t profile_bins = 0;
  std::size_t rdf_bins = 0;
  std::size_t histogram_bins = 0;
  bool voronoi = false;
  std::optional<double> order_margin;  // --order: bond order q6 at --tol, this margin (m)
  std::optional<SpreadRequest> spread;  // --spread: the layer statistics (spread_report.hpp)
};

struct RadiusSummary {
  double mean = 0, sd = 0, min = 0, max = 0;
};

// D10, D50, D90 of the bed's diameters on one basis (number, or volume as laser diffraction and
// powder data sheets report them).
struct DiameterQuantiles {
  bed::PsdBasis basis = bed::PsdBasis::number;
  double d10 = 0, d50 = 0, d90 = 0;
};
// The basis (or bases, "number+volume") the components of a target PSD were given on.
std::string psd_basis_text(const bed::Psd& psd);

struct BedReport {
  std::string file;
  bed::Bed bed;
  double box_density = 0;
  std::optional<double> layer_density;  // with a layer
  bed::ContactStats at_tol;
  std::vector<bed::ContactStats> by_tol;  // at kReportedTolerances
  double max_overlap = 0;
  RadiusSummary radius;
  DiameterQuantiles by_number, by_volume;
  std::optional<double> ks;
  std::optional<bed::Series> profile, rdf;
  std::optional<bed::Histogram> histogram;
  std::optional<bed::VoronoiStats> voronoi;
  std::optional<bed::OrderStats> order;
  std::optional<SpreadReport> spread;
};

// The statistics `req` asks for; `file` labels the report. Throws InputError for a 3D-only
// statistic on a 2D bed.
BedReport analyse_bed(bed::Bed bed, const std::string& file, const BedRequest& req);

// The report as one JSON object (an element of bedstat's "beds" array).
void write_bed_json(bed::JsonWriter& json, const BedReport& r, const BedRequest& req);

// The units of every number write_bed_json and write_spread_json write: bedstat's table
// (json_units.hpp).
std::span<const UnitEntry> bed_report_units();

}  // namespace powderbed::bed
