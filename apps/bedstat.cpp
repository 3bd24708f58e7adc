// bedstat: statistics of one or more beds (docs/bed-format.md, README "The programs"), as a table or one JSON object.
// Several beds print side by side: this is how geometric and dynamic beds are compared.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/app_main.hpp"
#include "common/contact_report.hpp"
#include "common/options.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/stats.hpp"

namespace {

using namespace powderbed;
namespace po = app::po;


struct Request {
  double tolerance = 1e-6;
  std::optional<std::pair<double, double>> layer;
  std::optional<bed::Psd> psd;
  std::size_t profile_bins = 0;
  std::size_t rdf_bins = 0;
  std::size_t histogram_bins = 0;
  bool voronoi = false;
  std::optional<double> order_margin;  // --order: bond order q6 at --tol, this margin
};

struct Report {
  std::string file;
  bed::Bed bed;
  double box_density = 0;
  double density = 0;  // the layer's when --layer
  bed::ContactStats at_tol;
  std::vector<bed::ContactStats> by_tol;
  double max_overlap = 0;
  double r_mean = 0, r_sd = 0, r_min = 0, r_max = 0;
  std::optional<double> ks;
  std::optional<bed::Series> profile, rdf;
  std::optional<bed::Histogram> histogram;
  std::optional<bed::VoronoiStats> voronoi;
  std::optional<bed::OrderStats> order;
};


Report analyse(const std::string& file, const Request& req, const bed::Domain* csv_domain) {
  Report r;
  r.file = file;
  r.bed = bed::read_bed_any(file, csv_domain);
  const bed::Bed& b = r.bed;
  r.box_density = bed::packing_density(b);
  r.density = req.layer ? bed::layer_density(b, req.layer->first, req.layer->second) : r.box_density;
  std::vector<double> tolerances(std::begin(app::kReportedTolerances), std::end(app::kReportedTolerances));
  tolerances.push_back(req.tolerance);
  r.by_tol = bed::contact_stats(b, tolerances);  // one neighbour search for all four
  r.at_tol = r.by_tol.back();
  r.by_tol.pop_back();
  r.max_overlap = bed::max_relative_overlap(b);
  if (b.n() > 0) {
    double sum = 0, sum2 = 0;
    r.r_min = r.r_max = b.radius[0];
    for (double rad : b.radius) {
      sum += rad;
      sum2 += rad * rad;
      r.r_min = std::min(r.r_min, rad);
      r.r_max = std::max(r.r_max, rad);
    }
    const double n = static_cast<double>(b.n());
    r.r_mean = sum / n;
    r.r_sd = std::sqrt(std::max(0.0, sum2 / n - r.r_mean * r.r_mean));
  }
  if (req.psd) r.ks = bed::ks_distance(b.radius, *req.psd);
  if (req.histogram_bins && b.n() > 0) {
    r.histogram = bed::radius_histogram(b, req.histogram_bins, req.psd ? &*req.psd : nullptr);
  }
  if (req.profile_bins) r.profile = bed::density_profile(b, req.profile_bins);
  if (req.rdf_bins && b.n() > 0) r.rdf = bed::radial_distribution(b, 5.0 * r.r_mean, req.rdf_bins);
  // 3D-only statistics are refused for a 2D bed rather than silently left out.
  if (req.voronoi && b.domain.dimension != 3) {
    throw InputError("--voronoi: " + file +
                     " is a 2D bed (accepted: 3D beds; the radical Voronoi tessellation is 3D only)");
  }
  if (req.order_margin && b.domain.dimension != 3) {
    throw InputError("--order: " + file + " is a 2D bed (accepted: 3D beds; q6 is 3D only)");
  }
  if (req.voronoi) r.voronoi = bed::voronoi_stats(b);
  if (req.order_margin) {
    r.order = bed::bond_order(b, req.tolerance, *req.order_margin);
  }
  return r;
}

void write_series(bed::JsonWriter& json, const std::string& key, const bed::Series& s) {
  json.begin_object(key).begin_array("x");
  for (double v : s.x) json.element(v);
  json.end_array().begin_array("y");
  for (double v : s.y) json.element(v);
  json.end_array().end_object();
}

void write_json_report(bed::JsonWriter& json, const Report& r, const Request& req) {
  json.begin_object();
  json.value("file", r.file)
      .value("n", std::uint64_t{r.bed.n()})
      .value("dimension", r.bed.domain.dimension)
      .value("density", r.density)
      .value("box_density", r.box_density);
  if (req.layer) {
    json.begin_object("layer")
        .value("z0", req.layer->first)
        .value("z1", req.layer->second)
        .value("density", r.density)
        .end_object();
  }
  json.value("tolerance", req.tolerance)
      .value("coordination", r.at_tol.coordination)
      .value("contacts", std::uint64_t{r.at_tol.contacts});
  json.begin_object("coordination_by_tol");
  for (const auto& c : r.by_tol) json.value(app::tolerance_key(c.tolerance), c.coordination);
  json.end_object();
  json.begin_array("contacts_histogram");
  for (std::size_t k : r.at_tol.histogram) json.element(static_cast<double>(k));
  json.end_array();
  json.value("rattlers", std::uint64_t{r.at_tol.rattlers})
      .value("wall_contacts", std::uint64_t{r.at_tol.wall_contacts})
      .value("max_overlap", r.max_overlap);
  json.begin_object("radius")
      .value("mean", r.r_mean)
      .value("sd", r.r_sd)
      .value("min", r.r_min)
      .value("max", r.r_max)
      .end_object();
  if (r.ks) json.value("ks_distance", *r.ks);
  if (r.histogram) {
    json.begin_object("radius_histogram").begin_array("edges");
    for (double v : r.histogram->edges) json.element(v);
    json.end_array().begin_array("counts");
    for (double v : r.histogram->counts) json.element(v);
    json.end_array();
    if (!r.histogram->target.empty()) {
      json.begin_array("target");
      for (double v : r.histogram->target) json.element(v);
      json.end_array();
    }
    json.end_object();
  }
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
  json.end_object();
}

// One row of the side-by-side table: a label and one cell per bed.
void table_row(std::ostream& out, const std::string& label, const std::vector<std::string>& cells) {
  out << std::left << std::setw(30) << label;
  for (const auto& c : cells) out << std::right << std::setw(16) << c;
  out << '\n';
}

template <class F>
std::vector<std::string> cells(const std::vector<Report>& reports, F&& f) {
  std::vector<std::string> out;
  for (const auto& r : reports) {
    std::ostringstream s;
    s << std::setprecision(6);
    f(s, r);
    out.push_back(s.str());
  }
  return out;
}

void print_table(std::ostream& out, const std::vector<Report>& reports, const Request& req) {
  table_row(out, "bed", cells(reports, [](auto& s, const Report& r) {
              const auto slash = r.file.find_last_of('/');
              s << (slash == std::string::npos ? r.file : r.file.substr(slash + 1));
            }));
  table_row(out, "particles", cells(reports, [](auto& s, const Report& r) { s << r.bed.n(); }));
  table_row(out, "dimension",
            cells(reports, [](auto& s, const Report& r) { s << r.bed.domain.dimension; }));
  table_row(out, "density (box)", cells(reports, [](auto& s, const Report& r) { s << r.box_density; }));
  if (req.layer) {
    std::ostringstream label;
    label << "density (layer " << req.layer->first << ".." << req.layer->second << ")";
    table_row(out, label.str(), cells(reports, [](auto& s, const Report& r) { s << r.density; }));
  }
  for (std::size_t t = 0; t < std::size(app::kReportedTolerances); ++t) {
    table_row(out, "coordination (tol " + app::tolerance_key(app::kReportedTolerances[t]) + ")",
              cells(reports, [t](auto& s, const Report& r) { s << r.by_tol[t].coordination; }));
  }
  const std::string at = " (tol " + app::tolerance_key(req.tolerance) + ")";
  if (std::find(std::begin(app::kReportedTolerances), std::end(app::kReportedTolerances), req.tolerance) ==
      std::end(app::kReportedTolerances)) {
    table_row(out, "coordination" + at,
              cells(reports, [](auto& s, const Report& r) { s << r.at_tol.coordination; }));
  }
  table_row(out, "rattlers" + at, cells(reports, [](auto& s, const Report& r) { s << r.at_tol.rattlers; }));
  table_row(out, "wall contacts" + at,
            cells(reports, [](auto& s, const Report& r) { s << r.at_tol.wall_contacts; }));
  std::size_t kmax = 0;
  for (const auto& r : reports) kmax = std::max(kmax, r.at_tol.histogram.size());
  for (std::size_t k = 0; k < kmax; ++k) {
    table_row(out, "  particles with " + std::to_string(k) + " contacts",
              cells(reports, [k](auto& s, const Report& r) {
                s << (k < r.at_tol.histogram.size() ? r.at_tol.histogram[k] : 0);
              }));
  }
  table_row(out, "max relative overlap", cells(reports, [](auto& s, const Report& r) { s << r.max_overlap; }));
  table_row(out, "radius mean (m)", cells(reports, [](auto& s, const Report& r) { s << r.r_mean; }));
  table_row(out, "radius sd (m)", cells(reports, [](auto& s, const Report& r) { s << r.r_sd; }));
  table_row(out, "radius min (m)", cells(reports, [](auto& s, const Report& r) { s << r.r_min; }));
  table_row(out, "radius max (m)", cells(reports, [](auto& s, const Report& r) { s << r.r_max; }));
  if (req.psd) {
    table_row(out, "KS distance to --psd", cells(reports, [](auto& s, const Report& r) { s << *r.ks; }));
  }
  if (req.voronoi) {
    table_row(out, "Voronoi local fraction mean", cells(reports, [](auto& s, const Report& r) {
                if (r.voronoi) s << r.voronoi->mean; else s << "-";
              }));
    table_row(out, "Voronoi local fraction sd", cells(reports, [](auto& s, const Report& r) {
                if (r.voronoi) s << r.voronoi->sd; else s << "-";
              }));
  }
  if (req.order_margin) {
    table_row(out, "q6 local mean" + at, cells(reports, [](auto& s, const Report& r) {
                if (r.order) s << r.order->q6_local_mean; else s << "-";
              }));
    table_row(out, "Q6 global" + at, cells(reports, [](auto& s, const Report& r) {
                if (r.order) s << r.order->q6_global; else s << "-";
              }));
  }
}

int run(int argc, char** argv) {
  po::options_description desc("bedstat options");
  app::add_common_options(desc);
  desc.add_options()("bed", po::value<std::vector<std::string>>()->multitoken(),
                     "bed file(s): .h5, .dump, or .csv with --domain; several print side by side")(
      "layer", po::value<std::string>(),
      "Z0,Z1 (m): report the density of the horizontal layer z in [Z0, Z1] (2D: y)")(
      "tol", po::value<double>()->default_value(1e-6),
      "relative contact tolerance: contact when d <= (ri + rj)(1 + tol)")(
      "psd", po::value<std::string>(), "target PSD (PSD string syntax): report the KS distance")(
      "domain", po::value<std::string>(), "xlo,ylo,zlo,xhi,yhi,zhi (m) for .csv beds")(
      "profile", po::value<std::size_t>()->default_value(0),
      "bins of the density profile phi(z) (JSON only; 0 = off)")(
      "histogram", po::value<std::size_t>()->default_value(0),
      "bins of the radius histogram, with the --psd target per bin (JSON only; 0 = off)")(
      "rdf", po::value<std::size_t>()->default_value(0),
      "bins of g(r) up to 5 mean radii (JSON only; 0 = off)")(
      "voronoi", "local packing fractions from the radical Voronoi tessellation (3D)")(
      "order", "bond-orientational order (3D): mean local q6 and global Q6, bonds = contacts at --tol")(
      "order-margin", po::value<double>()->default_value(0.0),
      "--order: average only over particles at least this far (m) from non-periodic faces");
  po::positional_options_description positional;
  positional.add("bed", -1);
  po::variables_map vm;
  if (!app::parse_options("bedstat", "bedstat BED [BED...] [options]", desc, positional, argc, argv,
                          vm)) {
    return 0;
  }
  if (!vm.count("bed")) throw InputError("no bed given (usage: bedstat BED [BED...] [options])");

  Request req;
  req.tolerance = vm["tol"].as<double>();
  if (!(req.tolerance >= 0) || !std::isfinite(req.tolerance)) {
    throw InputError("--tol: " + std::to_string(req.tolerance) + " (accepted: >= 0)");
  }
  if (vm.count("layer")) {
    const auto z = app::parse_number_list(vm["layer"].as<std::string>(), 2, 2, "--layer");
    if (!(z[1] > z[0])) {
      throw InputError("--layer: '" + vm["layer"].as<std::string>() + "' (accepted: Z0,Z1 with Z0 < Z1)");
    }
    req.layer = std::make_pair(z[0], z[1]);
  }
  if (vm.count("psd")) req.psd = bed::Psd::parse(vm["psd"].as<std::string>(), "--psd");
  // Bins are allocated per bed: a count beyond a million is a slip, refused before any work.
  constexpr std::size_t kMaxBins = 1000000;
  req.profile_bins = app::option_in_range<std::size_t>(vm, "profile", 0, kMaxBins, "0 = off");
  req.rdf_bins = app::option_in_range<std::size_t>(vm, "rdf", 0, kMaxBins, "0 = off");
  req.histogram_bins = app::option_in_range<std::size_t>(vm, "histogram", 0, kMaxBins, "0 = off");
  req.voronoi = vm.count("voronoi") > 0;
  if (vm.count("order")) {
    req.order_margin = vm["order-margin"].as<double>();
    if (!(*req.order_margin >= 0)) {
      std::ostringstream msg;
      msg << "--order-margin: " << *req.order_margin << " (accepted: >= 0 m)";
      throw InputError(msg.str());
    }
  }
  std::vector<app::PathArg> inputs;
  for (const auto& file : vm["bed"].as<std::vector<std::string>>()) inputs.push_back({"BED", file});
  app::check_paths(inputs, {});

  std::optional<bed::Domain> csv_domain;
  if (vm.count("domain")) csv_domain = app::parse_domain_bounds(vm["domain"].as<std::string>(), "--domain");

  std::vector<Report> reports;
  for (const auto& file : vm["bed"].as<std::vector<std::string>>()) {
    reports.push_back(analyse(file, req, csv_domain ? &*csv_domain : nullptr));
  }

  if (vm.count("json")) {
    bed::JsonWriter json;
    if (reports.size() == 1) {
      write_json_report(json, reports[0], req);
    } else {
      json.begin_object().begin_array("beds");
      for (const auto& r : reports) write_json_report(json, r, req);
      json.end_array().end_object();
    }
    std::cout << json.str() << '\n';
  } else {
    print_table(std::cout, reports, req);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return powderbed::app::run_app("bedstat", argc, argv, [&] { return run(argc, argv); });
}
