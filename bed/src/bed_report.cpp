#include "powderbed/bed/bed_report.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "powderbed/bed/contact_report.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/moments.hpp"

namespace powderbed::bed {

namespace {

RadiusSummary radius_summary(const std::vector<double>& radius) {
  RadiusSummary s;
  if (radius.empty()) return s;
  Moments moments;
  s.min = s.max = radius[0];
  for (double r : radius) {
    moments.add(r);
    s.min = std::min(s.min, r);
    s.max = std::max(s.max, r);
  }
  s.mean = moments.mean();
  s.sd = moments.sd();
  return s;
}

DiameterQuantiles diameter_quantiles(const std::vector<double>& radius, bed::PsdBasis basis) {
  return {basis, bed::sample_diameter_quantile(radius, 0.1, basis),
          bed::sample_diameter_quantile(radius, 0.5, basis),
          bed::sample_diameter_quantile(radius, 0.9, basis)};
}

void write_quantiles(bed::JsonWriter& json, const DiameterQuantiles& q) {
  json.begin_object(bed::basis_name(q.basis))
      .value("d10", q.d10)
      .value("d50", q.d50)
      .value("d90", q.d90)
      .end_object();
}

// 3D-only statistics are refused for a 2D bed rather than silently left out.
void check_dimension(const bed::Bed& b, const std::string& file, const BedRequest& req) {
  if (req.voronoi && b.domain.dimension != 3) {
    throw InputError(fmt::format("--voronoi: {} is a 2D bed (accepted: 3D beds; the radical "
                                 "Voronoi tessellation is 3D only)",
                                 file));
  }
  if (req.order_margin && b.domain.dimension != 3) {
    throw InputError(
        fmt::format("--order: {} is a 2D bed (accepted: 3D beds; q6 is 3D only)", file));
  }
}

void add_optional_statistics(BedReport& r, const BedRequest& req) {
  const bed::Bed& b = r.bed;
  if (req.psd) r.ks = bed::ks_distance(b.radius, *req.psd);
  if (req.histogram_bins && b.n() > 0) {
    r.histogram = bed::radius_histogram(b, req.histogram_bins, req.psd ? &*req.psd : nullptr);
  }
  if (req.profile_bins) r.profile = bed::density_profile(b, req.profile_bins);
  if (req.rdf_bins && b.n() > 0) {
    r.rdf = bed::radial_distribution(b, 5.0 * r.radius.mean, req.rdf_bins);
  }
  if (req.voronoi) r.voronoi = bed::voronoi_stats(b);
  if (req.order_margin) r.order = bed::bond_order(b, req.tolerance, *req.order_margin);
  if (req.spread) r.spread = analyse_spread(b, r.file, *req.spread);
}

void write_array(bed::JsonWriter& json, const std::string& key, const std::vector<double>& v) {
  json.begin_array(key);
  for (double x : v) json.element(x);
  json.end_array();
}

void write_series(bed::JsonWriter& json, const std::string& key, const bed::Series& s) {
  json.begin_object(key);
  write_array(json, "x", s.x);
  write_array(json, "y", s.y);
  json.end_object();
}

void write_contacts(bed::JsonWriter& json, const BedReport& r, const BedRequest& req) {
  json.value("tolerance", req.tolerance)
      .value("coordination", r.at_tol.coordination)
      .value("contacts", std::uint64_t{r.at_tol.contacts});
  json.begin_object("coordination_by_tol");
  for (const auto& c : r.by_tol) json.value(tolerance_key(c.tolerance), c.coordination);
  json.end_object();
  json.begin_array("contacts_histogram");
  for (std::size_t k : r.at_tol.histogram) json.element(static_cast<double>(k));
  json.end_array();
  json.value("rattlers", std::uint64_t{r.at_tol.rattlers})
      .value("wall_contacts", std::uint64_t{r.at_tol.wall_contacts})
      .value("max_overlap", r.max_overlap);
}

void write_radius(bed::JsonWriter& json, const BedReport& r, const BedRequest& req) {
  json.begin_object("radius")
      .value("mean", r.radius.mean)
      .value("sd", r.radius.sd)
      .value("min", r.radius.min)
      .value("max", r.radius.max)
      .end_object();
  json.begin_object("diameter_quantiles");
  write_quantiles(json, r.by_number);
  write_quantiles(json, r.by_volume);
  json.end_object();
  if (r.ks) json.value("ks_distance", *r.ks).value("psd_basis", psd_basis_text(*req.psd));
  if (!r.histogram) return;
  json.begin_object("radius_histogram");
  write_array(json, "edges", r.histogram->edges);
  write_array(json, "counts", r.histogram->counts);
  if (!r.histogram->target.empty()) write_array(json, "target", r.histogram->target);
  json.end_object();
}

void write_structure(bed::JsonWriter& json, const BedReport& r) {
  if (r.profile) write_series(json, "density_profile", *r.profile);
  if (r.rdf) write_series(json, "rdf", *r.rdf);
  if (r.voronoi) {
    json.begin_object("voronoi")
        .value("interior_cells", std::uint64_t{r.voronoi->interior})
        .value("local_fraction_mean", r.voronoi->mean)
        .value("local_fraction_sd", r.voronoi->sd)
        .end_object();
  }
  if (r.order) {
    json.value("q6_local_mean", r.order->q6_local_mean)
        .value("q6_global", r.order->q6_global)
        .value("q6_particles", std::uint64_t{r.order->particles});
  }
}

}  // namespace

std::string psd_basis_text(const bed::Psd& psd) {
  bool number = false, volume = false;
  for (const auto& c : psd.components())
    (c.basis == bed::PsdBasis::volume ? volume : number) = true;
  return number && volume ? "number+volume" : (volume ? "volume" : "number");
}

BedReport analyse_bed(bed::Bed bed, const std::string& file, const BedRequest& req) {
  check_dimension(bed, file, req);
  BedReport r;
  r.file = file;
  r.bed = std::move(bed);
  const bed::Bed& b = r.bed;
  r.box_density = bed::packing_density(b);
  if (req.layer) r.layer_density = bed::layer_density(b, req.layer->first, req.layer->second);
  std::vector<double> tolerances(std::begin(kReportedTolerances), std::end(kReportedTolerances));
  tolerances.push_back(req.tolerance);
  r.by_tol = bed::contact_stats(b, tolerances);  // one neighbour search for all four
  r.at_tol = r.by_tol.back();
  r.by_tol.pop_back();
  r.max_overlap = bed::max_relative_overlap(b);
  r.radius = radius_summary(b.radius);
  r.by_number = diameter_quantiles(b.radius, bed::PsdBasis::number);
  r.by_volume = diameter_quantiles(b.radius, bed::PsdBasis::volume);
  add_optional_statistics(r, req);
  return r;
}

void write_bed_json(bed::JsonWriter& json, const BedReport& r, const BedRequest& req) {
  json.begin_object();
  json.value("file", r.file)
      .value("n", std::uint64_t{r.bed.n()})
      .value("dimension", r.bed.domain.dimension)
      .value("box_density", r.box_density);
  if (r.layer_density) {
    json.begin_object("layer").value("z0", req.layer->first).value("z1", req.layer->second).end_object();
    json.value("layer_density", *r.layer_density);
  }
  write_contacts(json, r, req);
  write_radius(json, r, req);
  write_structure(json, r);
  if (r.spread) write_spread_json(json, *r.spread);
  json.end_object();
}

std::span<const UnitEntry> bed_report_units() {
  static constexpr UnitEntry kUnits[] = {
      {"n", "1"}, {"dimension", "1"}, {"box_density", "1"}, {"z0", "m"}, {"z1", "m"},
      {"layer_density", "1"},
      // contacts (write_contacts); coordination_by_tol is keyed by the relative tolerance
      {"tolerance", "1"}, {"coordination", "1"}, {"contacts", "1"}, {"1e-06", "1"},
      {"0.001", "1"}, {"0.01", "1"}, {"contacts_histogram", "1"}, {"rattlers", "1"},
      {"wall_contacts", "1"}, {"max_overlap", "1"},
      // radius, diameter quantiles, the PSD test and histogram
      {"mean", "m"}, {"sd", "m"}, {"min", "m"}, {"max", "m"}, {"d10", "m"}, {"d50", "m"},
      {"d90", "m"}, {"ks_distance", "1"}, {"edges", "m"}, {"counts", "1"}, {"target", "1"},
      // density profile (x: z) and g(r) (x: r)
      {"x", "m"}, {"y", "1"},
      {"interior_cells", "1"}, {"local_fraction_mean", "1"}, {"local_fraction_sd", "1"},
      {"q6_local_mean", "1"}, {"q6_global", "1"}, {"q6_particles", "1"},
      // spread (write_spread_json)
      {"plate", "m"}, {"gap", "m"}, {"window", "m"}, {"raster", "m"}, {"particles", "1"},
      {"density", "1"}, {"coverage", "1"}, {"mean_height", "m"}, {"sa", "m"}, {"sq", "m"},
      {"mean_diameter", "m"}, {"count", "1"}, {"slope", "1"}, {"d", "1"}, {"p", "1"},
      {"n_layer", "1"}, {"n_feed", "1"},
  };
  return kUnits;
}

}  // namespace powderbed::bed
