// bedstat: statistics of one or more beds (docs/bed-format.md, README "The programs"), as a table or one JSON object.
// Several beds print side by side: this is how geometric and dynamic beds are compared.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "common/app_main.hpp"
#include "powderbed/bed/bed_report.hpp"
#include "powderbed/bed/contact_report.hpp"
#include "common/options.hpp"
#include "powderbed/bed/spread_report.hpp"
#include "powderbed/bed/json_units.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/stats.hpp"
#include "powderbed/bed/stats_layer.hpp"

namespace {

using namespace powderbed;
namespace po = app::po;

using Report = bed::BedReport;
using Request = bed::BedRequest;

// The side-by-side table, gathered before it is printed so that every column is as wide as its
// widest cell (a long bed name) plus two spaces: columns never run together.
struct Table {
  std::vector<std::pair<std::string, std::vector<std::string>>> rows;

  void print(std::ostream& out) const {
    std::size_t label_width = 30;
    std::vector<std::size_t> width;
    for (const auto& [label, cells] : rows) {
      label_width = std::max(label_width, label.size() + 2);
      width.resize(std::max(width.size(), cells.size()), 16);
      for (std::size_t k = 0; k < cells.size(); ++k) width[k] = std::max(width[k], cells[k].size() + 2);
    }
    for (const auto& [label, cells] : rows) {
      out << std::left << std::setw(static_cast<int>(label_width)) << label;
      for (std::size_t k = 0; k < cells.size(); ++k)
        out << std::right << std::setw(static_cast<int>(width[k])) << cells[k];
      out << '\n';
    }
  }
};

// One row of the side-by-side table: a label and one cell per bed.
void table_row(Table& out, const std::string& label, const std::vector<std::string>& cells) {
  out.rows.emplace_back(label, cells);
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

// --spread rows (docs/spread-layer.md), after the bed's other statistics.
void print_spread_table(Table& out, const std::vector<Report>& reports) {
  auto row = [&](const std::string& label, auto&& f) {
    table_row(out, label, cells(reports, [&](auto& s, const Report& r) { f(s, *r.spread); }));
  };
  using Spread = bed::SpreadReport;
  row("spread: plate z (m)", [](auto& s, const Spread& p) { s << p.layer.request.plate; });
  row("spread: gap (m)", [](auto& s, const Spread& p) { s << p.layer.request.gap; });
  row("spread: window x0 (m)", [](auto& s, const Spread& p) { s << p.layer.request.x0; });
  row("spread: window x1 (m)", [](auto& s, const Spread& p) { s << p.layer.request.x1; });
  row("spread: raster cell (m)", [](auto& s, const Spread& p) { s << p.layer.map.dx; });
  row("spread: layer particles", [](auto& s, const Spread& p) { s << p.layer.particles; });
  row("spread: layer density", [](auto& s, const Spread& p) { s << p.layer.density; });
  row("spread: coverage", [](auto& s, const Spread& p) { s << p.layer.coverage; });
  row("spread: mean height (m)", [](auto& s, const Spread& p) { s << p.layer.mean_height; });
  row("spread: Sa (m)", [](auto& s, const Spread& p) { s << p.layer.sa; });
  row("spread: Sq (m)", [](auto& s, const Spread& p) { s << p.layer.sq; });
  row("spread: d(diameter)/dx", [](auto& s, const Spread& p) { s << p.layer.segregation.slope; });
  std::size_t bins = 0;
  for (const auto& r : reports) bins = std::max(bins, r.spread->layer.segregation.x.size());
  for (std::size_t k = 0; k < bins; ++k) {
    row("  mean diameter, x bin " + std::to_string(k), [k](auto& s, const Spread& p) {
      const auto& seg = p.layer.segregation;
      if (k < seg.x.size() && seg.count[k] > 0) s << seg.mean_diameter[k]; else s << "-";
    });
  }
  row("spread: KS D to feed", [](auto& s, const Spread& p) { if (p.ks) s << p.ks->d; else s << "-"; });
  row("spread: KS p", [](auto& s, const Spread& p) { if (p.ks) s << p.ks->p; else s << "-"; });
}

void print_table(Table& out, const std::vector<Report>& reports, const Request& req) {
  table_row(out, "bed", cells(reports, [](auto& s, const Report& r) {
              const auto slash = r.file.find_last_of('/');
              s << (slash == std::string::npos ? r.file : r.file.substr(slash + 1));
            }));
  table_row(out, "particles", cells(reports, [](auto& s, const Report& r) { s << r.bed.n(); }));
  table_row(out, "dimension",
            cells(reports, [](auto& s, const Report& r) { s << r.bed.domain.dimension; }));
  table_row(out, "density (box)", cells(reports, [](auto& s, const Report& r) { s << r.box_density; }));
  if (req.layer) {
    const std::string label =
        fmt::format("density (layer {:g}..{:g})", req.layer->first, req.layer->second);
    table_row(out, label, cells(reports, [](auto& s, const Report& r) { s << *r.layer_density; }));
  }
  for (std::size_t t = 0; t < std::size(bed::kReportedTolerances); ++t) {
    table_row(out, "coordination (tol " + bed::tolerance_key(bed::kReportedTolerances[t]) + ")",
              cells(reports, [t](auto& s, const Report& r) { s << r.by_tol[t].coordination; }));
  }
  const std::string at = " (tol " + bed::tolerance_key(req.tolerance) + ")";
  if (std::find(std::begin(bed::kReportedTolerances), std::end(bed::kReportedTolerances), req.tolerance) ==
      std::end(bed::kReportedTolerances)) {
    table_row(out, "coordination" + at,
              cells(reports, [](auto& s, const Report& r) { s << r.at_tol.coordination; }));
  }
  // A particle on the floor or against a wall is held: only those touching nothing are rattlers.
  table_row(out, "rattlers (no particle/wall)" + at, cells(reports, [](auto& s, const Report& r) { s << r.at_tol.rattlers; }));
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
  table_row(out, "radius mean (m)", cells(reports, [](auto& s, const Report& r) { s << r.radius.mean; }));
  table_row(out, "radius sd (m)", cells(reports, [](auto& s, const Report& r) { s << r.radius.sd; }));
  table_row(out, "radius min (m)", cells(reports, [](auto& s, const Report& r) { s << r.radius.min; }));
  table_row(out, "radius max (m)", cells(reports, [](auto& s, const Report& r) { s << r.radius.max; }));
  using Quantiles = bed::DiameterQuantiles;
  for (const auto& [basis, q] : {std::pair{"number", &Report::by_number},
                                 std::pair{"volume", &Report::by_volume}}) {
    for (const auto& [label, d] :
         {std::pair{"D10", &Quantiles::d10}, std::pair{"D50", &Quantiles::d50},
          std::pair{"D90", &Quantiles::d90}}) {
      table_row(out, std::string(label) + " diameter, " + basis + " basis (m)",
                cells(reports, [q = q, d = d](auto& s, const Report& r) { s << (r.*q).*d; }));
    }
  }
  if (req.psd) {
    table_row(out, "KS distance to --psd", cells(reports, [](auto& s, const Report& r) { s << *r.ks; }));
    table_row(out, "--psd basis",
              std::vector<std::string>(reports.size(), bed::psd_basis_text(*req.psd)));
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
  if (req.spread) print_spread_table(out, reports);
}

// The statistics the options ask for; throws InputError naming the option on bad values.
Request parse_request(const po::variables_map& vm) {
  Request req;
  req.tolerance = vm["tol"].as<double>();
  if (!(req.tolerance >= 0) || !std::isfinite(req.tolerance)) {
    throw InputError(fmt::format("--tol: {:f} (accepted: >= 0)", req.tolerance));
  }
  if (vm.count("layer")) {
    const auto z = app::parse_number_list(vm["layer"].as<std::string>(), 2, 2, "--layer");
    if (!(z[1] > z[0])) {
      throw InputError(fmt::format("--layer: '{}' (accepted: Z0,Z1 with Z0 < Z1)",
                                   vm["layer"].as<std::string>()));
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
      throw InputError(fmt::format("--order-margin: {:g} (accepted: >= 0 m)", *req.order_margin));
    }
  }
  return req;
}

// The --spread options make sense only with --spread; --height-map and --feed are paths.
void check_spread_options(const po::variables_map& vm, std::size_t beds,
                          std::vector<app::PathArg>& inputs, std::vector<app::PathArg>& outputs) {
  for (const char* name : {"plate", "gap", "window", "raster", "height-map", "feed"}) {
    if (vm.count(name) && !vm.count("spread")) {
      throw InputError(
          fmt::format("--{}: given without --spread (accepted: with --spread)", name));
    }
  }
  if (vm.count("height-map")) {
    if (beds != 1) {
      throw InputError(fmt::format("--height-map: {} beds given (accepted: one bed)", beds));
    }
    outputs.push_back({"--height-map", vm["height-map"].as<std::string>()});
    app::check_extension(outputs.back(), {".csv"});
  }
  if (vm.count("feed")) inputs.push_back({"--feed", vm["feed"].as<std::string>()});
}

// --spread's options (docs/spread-layer.md); the gap and the feed may also come from each bed.
bed::SpreadRequest parse_spread_request(const po::variables_map& vm,
                                        const std::optional<bed::Domain>& csv_domain) {
  bed::SpreadRequest sp;
  auto positive = [&](const char* name) {
    const double v = vm[name].as<double>();
    if (!(v > 0)) {
      throw InputError(fmt::format("--{}: {:g} (accepted: > 0 m)", name, v));
    }
    return v;
  };
  if (vm.count("plate")) sp.plate = vm["plate"].as<double>();
  if (vm.count("gap")) sp.gap = positive("gap");
  if (vm.count("raster")) sp.raster = positive("raster");
  if (vm.count("window")) {
    const auto x = app::parse_number_list(vm["window"].as<std::string>(), 2, 2, "--window");
    if (!(x[1] > x[0])) {
      throw InputError(fmt::format("--window: '{}' (accepted: X0,X1 with X0 < X1)",
                                   vm["window"].as<std::string>()));
    }
    sp.window = std::make_pair(x[0], x[1]);
  }
  sp.segregation_bins = app::option_in_range<std::size_t>(vm, "segregation-bins", 1, 1000000);
  if (vm.count("height-map")) sp.height_map = vm["height-map"].as<std::string>();
  if (vm.count("feed")) {
    const std::string file = vm["feed"].as<std::string>();
    const bed::Bed feed = bed::read_bed_any(file, csv_domain ? &*csv_domain : nullptr);
    bed::SpreadFeed f;
    f.source = file;
    for (const double r : feed.radius) f.diameters.push_back(2.0 * r);
    sp.feed = std::move(f);
  }
  return sp;
}

// bedstat's options with their help: one entry per option, so the list is as long as it is.
void add_options(po::options_description& desc) {
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
      "--order: average only over particles at least this far (m) from non-periodic faces")(
      "spread", "spread-layer statistics (docs/spread-layer.md): density between --plate and "
                "--plate + --gap, coverage, height map Sa/Sq, segregation along x, KS to the feed")(
      "plate", po::value<double>(), "--spread: z of the build plate (m; default: the domain floor)")(
      "gap", po::value<double>(),
      "--spread: layer thickness (m): top = plate + gap (default: the bed's recorded recoater.gap)")(
      "window", po::value<std::string>(),
      "--spread: X0,X1 (m): the part of the strip to measure, leaving out its ends (default: all)")(
      "raster", po::value<double>(), "--spread: height-map cell (m; default: mean radius / 10)")(
      "segregation-bins", po::value<std::size_t>()->default_value(10),
      "--spread: x bins of the mean diameter")(
      "height-map", po::value<std::string>(),
      "--spread: write the height map as CSV x,y,height,covered (m; one bed only)")(
      "feed", po::value<std::string>(),
      "--spread: bed of the feed powder for the two-sample KS test (default: the bed's recorded PSD)");
}

// Each bed read and analysed as `req` asks; a text bed printed too coarsely for --tol (a dump at
// LAMMPS's default 6 digits) gets a warning.
std::vector<Report> analyse_beds(const std::vector<std::string>& files, const Request& req,
                                 const std::optional<bed::Domain>& csv_domain) {
  std::vector<Report> reports;
  for (const auto& file : files) {
    bed::Bed b = bed::read_bed_any(file, csv_domain ? &*csv_domain : nullptr);
    const std::string warning = bed::printed_precision_warning(b, req.tolerance);
    if (!warning.empty()) std::cerr << "bedstat: warning: " << file << ": " << warning << '\n';
    reports.push_back(bed::analyse_bed(std::move(b), file, req));
  }
  return reports;
}

int run(int argc, char** argv) {
  po::options_description desc("bedstat options");
  add_options(desc);
  po::positional_options_description positional;
  positional.add("bed", -1);
  po::variables_map vm;
  if (!app::parse_options("bedstat", "bedstat BED [BED...] [options]", desc, positional, argc, argv,
                          vm)) {
    return 0;
  }
  if (!vm.count("bed")) throw InputError("no bed given (usage: bedstat BED [BED...] [options])");

  Request req = parse_request(vm);
  const auto& files = vm["bed"].as<std::vector<std::string>>();
  std::vector<app::PathArg> inputs, outputs;
  for (const auto& file : files) inputs.push_back({"BED", file});
  check_spread_options(vm, files.size(), inputs, outputs);
  app::check_paths(inputs, outputs);

  std::optional<bed::Domain> csv_domain;
  if (vm.count("domain")) csv_domain = app::parse_domain_bounds(vm["domain"].as<std::string>(), "--domain");
  if (vm.count("spread")) req.spread = parse_spread_request(vm, csv_domain);
  const std::vector<Report> reports = analyse_beds(files, req, csv_domain);

  if (req.spread && !req.spread->height_map.empty()) {
    bed::write_height_map_csv(reports.front().spread->layer.map, req.spread->height_map);
  }
  if (vm.count("json")) {
    // Always {"beds": [...]}, one entry per bed, however many beds: one shape to parse.
    bed::JsonWriter json;
    json.begin_object().begin_array("beds");
    for (const auto& r : reports) bed::write_bed_json(json, r, req);
    json.end_array();
    bed::write_units(json, bed::bed_report_units());
    json.end_object();
    std::cout << json.str() << '\n';
  } else {
    Table table;
    print_table(table, reports, req);
    table.print(std::cout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return powderbed::app::run_app("bedstat", argc, argv, [&] { return run(argc, argv); });
}
