#include "powderbed/bed/spread_report.hpp"

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

namespace {

// The recorded scene's keys for the recoater's gap and the supply's PSD (deposit's option names;
// a bed records its resolved options, apps/common/options.hpp scene_text).
constexpr const char* kGapKey = "recoater.gap";
constexpr const char* kPsdKeys[] = {"supply.psd", "psd"};

double recorded_gap(const bed::Bed& b, const std::string& file) {
  const auto text = scene_value(b.provenance.scene, kGapKey);
  if (!text) {
    throw InputError(fmt::format("--gap: missing for {} (required: the bed records no "
                                 "recoater.gap; accepted: a height > 0 m)",
                                 file));
  }
  char* end = nullptr;
  const double gap = std::strtod(text->c_str(), &end);
  if (end == text->c_str() || *end != '\0' || !std::isfinite(gap)) {
    throw InputError(fmt::format(
        "{}: recorded recoater.gap '{}' is not a number (accepted: give --gap H in m)", file,
        *text));
  }
  return gap;
}

double mean_radius(const bed::Bed& b) {
  double sum = 0;
  for (const double r : b.radius) sum += r;
  return b.n() ? sum / static_cast<double>(b.n()) : 0.0;
}

bed::LayerRequest layer_request(const bed::Bed& b, const std::string& file,
                                const SpreadRequest& req, std::string& gap_source) {
  bed::LayerRequest q;
  q.plate = req.plate.value_or(b.domain.lower[2]);
  if (req.gap) {
    q.gap = *req.gap;
    gap_source = "--gap";
  } else {
    q.gap = recorded_gap(b, file);
    gap_source = "recoater.gap of the bed";
  }
  q.x0 = req.window ? req.window->first : b.domain.lower[0];
  q.x1 = req.window ? req.window->second : b.domain.upper[0];
  // A tenth of the mean radius: cell-centre samples of randomly placed spheres are unbiased for
  // the coverage and mean height at any cell size, and the worst case, a monolayer lattice
  // aligned with the raster, is within 1.6 % in Sa there (docs/spread-layer.md).
  if (req.raster) {
    q.raster = *req.raster;
  } else if (b.n() > 0) {
    q.raster = 0.1 * mean_radius(b);
  } else {
    throw InputError(fmt::format("--raster: missing for {} (required for a bed with no "
                                 "particles; accepted: a cell size > 0 m)",
                                 file));
  }
  q.segregation_bins = req.segregation_bins;
  return q;
}

// The layer's sizes against --feed, else against the PSD the bed records, else nothing.
void add_ks(SpreadReport& s, const bed::Bed& b, const SpreadRequest& req) {
  if (req.feed) {
    s.feed_source = req.feed->source;
    s.ks = req.feed->psd ? bed::ks_against_psd(s.layer.diameters, *req.feed->psd)
                         : bed::ks_two_sample(s.layer.diameters, req.feed->diameters);
    return;
  }
  for (const char* key : kPsdKeys) {
    if (const auto text = scene_value(b.provenance.scene, key)) {
      s.feed_source = *text;
      s.ks = bed::ks_against_psd(s.layer.diameters, bed::Psd::parse(*text, key));
      return;
    }
  }
}

}  // namespace

std::optional<std::string> scene_value(const std::string& scene, const std::string& key) {
  std::istringstream in(scene);
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    auto trim = [](std::string s) {
      const auto a = s.find_first_not_of(" \t\r"), z = s.find_last_not_of(" \t\r");
      return a == std::string::npos ? std::string() : s.substr(a, z - a + 1);
    };
    if (trim(line.substr(0, eq)) == key) return trim(line.substr(eq + 1));
  }
  return std::nullopt;
}

SpreadReport analyse_spread(const bed::Bed& b, const std::string& file, const SpreadRequest& req) {
  if (b.domain.dimension != 3) {
    throw InputError(fmt::format(
        "--spread: {} is a 2D bed (accepted: 3D beds; a layer has a top view)", file));
  }
  SpreadReport s;
  s.layer = bed::layer_stats(b, layer_request(b, file, req, s.gap_source));
  add_ks(s, b, req);
  return s;
}

void write_spread_json(bed::JsonWriter& json, const SpreadReport& s) {
  const bed::LayerStats& l = s.layer;
  const bed::LayerRequest& q = l.request;
  json.begin_object("spread")
      .value("plate", q.plate)
      .value("gap", q.gap)
      .value("gap_source", s.gap_source);
  json.begin_array("window").element(q.x0).element(q.x1).end_array();
  json.begin_array("raster").element(l.map.dx).element(l.map.dy).end_array();
  json.value("particles", std::uint64_t{l.particles})
      .value("density", l.density)
      .value("coverage", l.coverage)
      .value("mean_height", l.mean_height)
      .value("sa", l.sa)
      .value("sq", l.sq);
  json.begin_object("segregation");
  json.begin_array("x");
  for (const double x : l.segregation.x) json.element(x);
  json.end_array().begin_array("mean_diameter");
  for (const double d : l.segregation.mean_diameter) json.element(d);
  json.end_array().begin_array("count");
  for (const std::size_t c : l.segregation.count) json.element(static_cast<double>(c));
  json.end_array().value("slope", l.segregation.slope).end_object();
  if (s.ks) {
    json.begin_object("psd_ks")
        .value("feed", s.feed_source)
        .value("d", s.ks->d)
        .value("p", s.ks->p)
        .value("n_layer", std::uint64_t{s.ks->n1})
        .value("n_feed", std::uint64_t{s.ks->n2})
        .end_object();
  }
  json.end_object();
}

}  // namespace powderbed::bed
