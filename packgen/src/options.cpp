// Validation and parsing of the packing options (docs/physics.md §3).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <sstream>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/packgen/pack.hpp"
#include "powderbed/packgen/raster_grid.hpp"

namespace powderbed::packgen {

namespace {

[[noreturn]] void fail(const std::string& text) { throw InputError(text); }

// The domain's lengths joined by `separator`, each with 6 significant digits as the messages
// print every double ({:g}).
std::string lengths(const bed::Domain& domain, const char* separator) {
  std::vector<double> length;
  for (int a = 0; a < domain.dimension; ++a) length.push_back(domain.length(a));
  return fmt::format("{:g}", fmt::join(length, separator));
}

// How many particles of radius r the domain holds at density 1, the bound no packing reaches.
double domain_holds(const bed::Domain& domain, double r) {
  const double pi = 3.14159265358979323846;
  const double each = domain.dimension == 3 ? bed::sphere_volume(r) : pi * r * r;
  return domain.measure() / each;
}

void check_phases(const bed::Domain& domain, const PackOptions& o) {
  if (o.phases.empty()) fail("--phases: no phase given (accepted: e.g. 0:0.3,1)");
  for (const Phase& p : o.phases) {
    if (p.approach < 0 || p.approach > 3) {
      fail("--approach: " + std::to_string(p.approach) + " (accepted: 0, 1, 2 or 3 contacts)");
    }
    if (p.approach == 3 && domain.dimension == 2) {
      fail("--approach: 3 needs a 3D domain (accepted in 2D: 0, 1 or 2 contacts)");
    }
  }
}

// The numbers of the placement and its stop rules, each in its range.
void check_numbers(const PackOptions& o) {
  if (o.tries < 1) fail("--tries: " + std::to_string(o.tries) + " (accepted: >= 1)");
  if (o.directions && *o.directions < 1) {
    fail("--directions: " + std::to_string(*o.directions) + " (accepted: >= 1)");
  }
  if (o.retire_after < 0) {
    fail("--retire-after: " + std::to_string(o.retire_after) + " (accepted: >= 0, 0 = never)");
  }
  if (o.max_failures && *o.max_failures < 1) fail("--max-failures: 0 (accepted: >= 1)");
  if (o.target_density != 0 && !(o.target_density > 0 && o.target_density < 1)) {
    fail(fmt::format("--target-density: {:g} (accepted: 0 < F < 1)", o.target_density));
  }
  if (o.count > 0 && o.target_density > 0) {
    fail("--count and --target-density: give one stop rule, not both");
  }
  if (!(o.edge_fraction >= 0 && o.edge_fraction <= 1)) {
    fail(fmt::format("--edge-fraction: {:g} (accepted: 0 <= F <= 1)", o.edge_fraction));
  }
  if (!(o.floor_seed >= 0 && o.floor_seed < 1)) {
    fail(fmt::format("--floor-seed: {:g} (accepted: 0 <= F < 1)", o.floor_seed));
  }
}

// The domain against the PSD: no smaller than the smallest particle, and, unless allow_huge,
// no larger than max_particles of the mean size (docs/hardening.md: a unit slip) and no --count
// above max_particles.
void check_domain_size(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& o) {
  const double d_min = 2 * psd.min_radius();
  double shortest = domain.length(0);
  for (int a = 1; a < domain.dimension; ++a) shortest = std::min(shortest, domain.length(a));
  if (shortest < d_min) {
    fail(fmt::format("--domain: {} is smaller than the smallest particle diameter {:g}",
                     lengths(domain, " x "), d_min));
  }
  const double by_mean = domain_holds(domain, psd.mean_radius());
  if (!o.allow_huge && by_mean > o.max_particles) {
    fail(fmt::format(
        "--domain: {} m would hold about {:g} particles of the PSD's mean diameter {:g} m "
        "(accepted: up to {:g}; lengths in um instead of m? e.g. {:g}e-6; --allow-huge if meant)",
        lengths(domain, ","), by_mean, 2 * psd.mean_radius(), o.max_particles,
        domain.length(0)));
  }
  if (o.count > (std::size_t{1} << 20)) check_count_fits(domain, psd, o.count);
  if (o.count > 0 && !o.allow_huge && static_cast<double>(o.count) > o.max_particles) {
    fail(fmt::format("--count: {} (accepted: up to {:g} particles; --allow-huge if meant)",
                     o.count, o.max_particles));
  }
}

void check_raster(const bed::Domain& domain, const PackOptions& o) {
  if (!(o.raster_spacing > 0) || !std::isfinite(o.raster_spacing)) {
    fail(fmt::format("--raster-spacing: {:g} (accepted: a spacing > 0 in m)", o.raster_spacing));
  }
  const double finest = RasterGrid::finest_spacing(domain, o.raster_max_bytes);
  if (o.raster_spacing < finest) {
    fail(fmt::format(
        "--raster-spacing: {:g} needs more than {:g} GiB for the status grid (the finest allowed "
        "for this domain is {:g})",
        o.raster_spacing, static_cast<double>(o.raster_max_bytes) / (1 << 30), finest));
  }
}

}  // namespace

int directions_for(const PackOptions& options, int dimension) {
  return options.directions.value_or(dimension == 2 ? kDirections2D : kDirections3D);
}

void check_count_fits(const bed::Domain& domain, const bed::Psd& psd, std::size_t count) {
  const double by_min = domain_holds(domain, psd.min_radius());
  if (static_cast<double>(count) > by_min) {
    fail(fmt::format(
        "--count: {} particles cannot fit in the domain (accepted: at most {:g}, the domain's {} "
        "over the smallest particle's)",
        count, std::floor(by_min), domain.dimension == 3 ? "volume" : "area"));
  }
}

void validate(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& o) {
  domain.validate("--domain");
  check_phases(domain, o);
  check_numbers(o);
  check_domain_size(domain, psd, o);
  if (o.collision == Collision::raster) check_raster(domain, o);
}

std::vector<Phase> parse_phases(const std::string& text, const std::string& option) {
  std::vector<Phase> phases;
  std::stringstream in(text);
  std::string item;
  const std::string accepted = " (accepted: approach[:density],... e.g. 0:0.3,1)";
  double last = 0;
  while (std::getline(in, item, ',')) {
    const auto colon = item.find(':');
    Phase p;
    try {
      std::size_t used = 0;
      const std::string a = item.substr(0, colon);
      p.approach = std::stoi(a, &used);
      if (used != a.size()) throw std::invalid_argument(a);
      if (colon != std::string::npos) {
        const std::string d = item.substr(colon + 1);
        p.until_density = std::stod(d, &used);
        if (used != d.size()) throw std::invalid_argument(d);
      }
    } catch (const std::exception&) {
      fail(option + ": '" + text + "' cannot be read" + accepted);
    }
    if (colon != std::string::npos && !(p.until_density > last && p.until_density < 1)) {
      fail(fmt::format("{}: '{}' has density {:g} (accepted: increasing densities in (0, 1))",
                       option, text, p.until_density));
    }
    if (colon != std::string::npos) last = p.until_density;
    phases.push_back(p);
  }
  if (phases.empty()) fail(option + ": '" + text + "' has no phase" + accepted);
  for (std::size_t i = 0; i + 1 < phases.size(); ++i) {
    if (phases[i].until_density >= 1) {
      fail(option + ": '" + text + "': every phase but the last needs :density" + accepted);
    }
  }
  return phases;
}

Collision parse_collision(const std::string& text, const std::string& option) {
  if (text == "raster") return Collision::raster;
  if (text == "grid") return Collision::grid;
  if (text == "kdtree") return Collision::kdtree;
  fail(option + ": '" + text + "' (accepted: raster, grid or kdtree)");
}

SiteOrder parse_site_order(const std::string& text, const std::string& option) {
  if (text == "random") return SiteOrder::random;
  if (text == "lowest") return SiteOrder::lowest;
  fail(option + ": '" + text + "' (accepted: random or lowest)");
}

const char* site_order_name(SiteOrder s) { return s == SiteOrder::random ? "random" : "lowest"; }

const char* collision_name(Collision c) {
  switch (c) {
    case Collision::raster: return "raster";
    case Collision::grid: return "grid";
    case Collision::kdtree: return "kdtree";
  }
  return "grid";
}

}  // namespace powderbed::packgen
