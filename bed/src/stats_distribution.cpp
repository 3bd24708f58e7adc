// Size and pair distributions of docs/physics.md §2: radius histogram against the target PSD, and the
// radial distribution function g(r).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/neighbours.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/bed/stats.hpp"

namespace powderbed::bed {

// docs/physics.md §2 "PSD histogram vs target". A single size (zero-width window) gets the window
// r (1 -+ 0.005) so that it has a bin. With a target PSD the window is the PSD's; radii outside
// it are not counted, so counts summing to less than N show sizes the PSD cannot produce.
Histogram radius_histogram(const Bed& bed, std::size_t bins, const Psd* target) {
  if (bins == 0) throw InputError("radius_histogram: bins is 0 (accepted: >= 1)");
  double lo = 0, hi = 0;
  if (target != nullptr) {
    lo = target->min_radius();
    hi = target->max_radius();
  } else if (bed.n() == 0) {
    throw InputError("radius_histogram: bed has no particles and no target PSD (accepted: one of them)");
  } else {
    const auto [mn, mx] = std::minmax_element(bed.radius.begin(), bed.radius.end());
    lo = *mn;
    hi = *mx;
  }
  if (!(hi > lo)) {
    lo *= 0.995;
    hi *= 1.005;
  }
  Histogram h;
  h.edges.resize(bins + 1);
  const double width = (hi - lo) / static_cast<double>(bins);
  for (std::size_t k = 0; k < bins; ++k) h.edges[k] = lo + static_cast<double>(k) * width;
  h.edges[bins] = hi;
  h.counts.assign(bins, 0.0);
  const double last = static_cast<double>(bins - 1);
  for (const double r : bed.radius) {
    if (!(r >= lo && r <= hi)) continue;
    const double k = std::min(std::floor((r - lo) / width), last);
    h.counts[static_cast<std::size_t>(k)] += 1.0;
  }
  if (target != nullptr) {
    const auto n = static_cast<double>(bed.n());
    h.target.resize(bins);
    for (std::size_t k = 0; k < bins; ++k) {
      h.target[k] = n * (target->cdf_radius(h.edges[k + 1]) - target->cdf_radius(h.edges[k]));
    }
  }
  return h;
}

// docs/physics.md §2 g(r): pair counts in shells around the centres at least r_max from every
// non-periodic face, divided by the ideal-gas count (N - 1)/V times the shell measure (so an
// uncorrelated bed of N particles gives g = 1 without a 1/N bias).
Series radial_distribution(const Bed& bed, double r_max, std::size_t bins) {
  const Domain& d = bed.domain;
  d.validate("radial_distribution");
  if (bins == 0) throw InputError("radial_distribution: bins is 0 (accepted: >= 1)");
  if (!std::isfinite(r_max) || !(r_max > 0)) {
    throw InputError(
        fmt::format("radial_distribution: r_max {:g} (accepted: > 0, finite)", r_max));
  }
  for (int a = 0; a < d.dimension; ++a) {
    if (d.periodic[a] && r_max > 0.5 * d.length(a)) {
      throw InputError(fmt::format(
          "radial_distribution: r_max {:g} exceeds half the periodic length {:g} on axis {} "
          "(accepted: <= {:g})",
          r_max, d.length(a), "xyz"[a], 0.5 * d.length(a)));
    }
  }
  const std::size_t n = bed.n();
  if (n < 2) throw InputError("radial_distribution: bed has fewer than 2 particles (accepted: >= 2)");
  const std::vector<double>* centre[3] = {&bed.x, &bed.y, &bed.z};
  std::vector<char> is_centre(n, 1);
  std::size_t centres = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < d.dimension; ++a) {
      const double c = (*centre[a])[i];
      if (!d.periodic[a] && (c - d.lower[a] < r_max || d.upper[a] - c < r_max)) is_centre[i] = 0;
    }
    centres += is_centre[i] ? 1 : 0;
  }
  if (centres == 0) {
    throw InputError(fmt::format(
        "radial_distribution: no particle is at least r_max {:g} from the walls (accepted: r_max "
        "leaving some particles as centres)",
        r_max));
  }
  const double step = r_max / static_cast<double>(bins);
  const double last = static_cast<double>(bins - 1);
  std::vector<double> count(bins, 0.0);
  for (const NeighbourPair& p : pairs_within_cell_list(bed, r_max)) {
    const auto k = static_cast<std::size_t>(std::min(std::floor(p.distance / step), last));
    count[k] += is_centre[p.i] + is_centre[p.j];
  }
  const double density = static_cast<double>(n - 1) / d.measure();
  Series g;
  g.x.resize(bins);
  g.y.resize(bins);
  for (std::size_t k = 0; k < bins; ++k) {
    const double r0 = static_cast<double>(k) * step, r1 = k == bins - 1 ? r_max : r0 + step;
    const double shell = d.dimension == 3
                             ? sphere_volume(r1) - sphere_volume(r0)
                             : std::numbers::pi * (r1 * r1 - r0 * r0);
    g.x[k] = 0.5 * (r0 + r1);
    g.y[k] = count[k] / (static_cast<double>(centres) * density * shell);
  }
  return g;
}

}  // namespace powderbed::bed
