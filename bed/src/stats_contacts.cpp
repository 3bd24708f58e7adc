// Contact statistics of SPEC.md §2: coordination number, contacts per particle, rattlers, wall
// contacts, and the largest relative overlap.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "neighbours_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/stats.hpp"

namespace powderbed::bed {

// SPEC.md §2: a pair touches when d_ij <= (r_i + r_j)(1 + tol); Z = 2 contacts / N. A particle
// touches a non-periodic face when its centre is within r (1 + tol) of it (2D: x and y faces).
ContactStats contact_stats(const Bed& bed, double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance > -1)) {
    std::ostringstream msg;
    msg << "contact_stats: tolerance " << tolerance << " (accepted: finite, > -1)";
    throw InputError(msg.str());
  }
  detail::check_pair_index_range(bed, "contact_stats");
  ContactStats out;
  out.tolerance = tolerance;
  const std::size_t n = bed.n();
  if (n == 0) return out;
  const detail::PairGeometry geometry(bed);
  const double scale = 1.0 + tolerance;
  std::vector<std::uint32_t> per_particle(n, 0);
  std::size_t contacts = 0;
  if (n > 1) {
    const detail::CellList cells(geometry, 2.0 * detail::max_radius(bed) * std::max(scale, 1.0));
    const double* r = bed.radius.data();
    cells.for_each_candidate([&](std::uint32_t i, std::uint32_t j, double d2) {
      const double reach = (r[i] + r[j]) * scale;
      // Cheap squared pre-test (widened past rounding), then the exact rule on d itself.
      if (d2 <= reach * reach * (1.0 + 1e-12) && std::sqrt(d2) <= reach) {
        ++per_particle[i];
        ++per_particle[j];
        ++contacts;
      }
    });
  }
  out.contacts = contacts;
  out.coordination = 2.0 * static_cast<double>(contacts) / static_cast<double>(n);
  const std::uint32_t most = *std::max_element(per_particle.begin(), per_particle.end());
  out.histogram.assign(std::size_t{most} + 1, 0);
  for (const std::uint32_t k : per_particle) ++out.histogram[k];
  out.rattlers = out.histogram[0];

  const Domain& d = bed.domain;
  const std::vector<double>* centre[3] = {&bed.x, &bed.y, &bed.z};
  for (int a = 0; a < d.dimension; ++a) {
    if (d.periodic[a]) continue;
    const std::vector<double>& c = *centre[a];
    for (std::size_t i = 0; i < n; ++i) {
      const double reach = bed.radius[i] * scale;
      if (c[i] - d.lower[a] <= reach) ++out.wall_contacts;
      if (d.upper[a] - c[i] <= reach) ++out.wall_contacts;
    }
  }
  return out;
}

// SPEC.md §2 overlap check: max over pairs of (r_i + r_j - d) / (r_i + r_j).
double max_relative_overlap(const Bed& bed) {
  detail::check_pair_index_range(bed, "max_relative_overlap");
  if (bed.n() < 2) return 0.0;
  const detail::PairGeometry geometry(bed);
  const detail::CellList cells(geometry, 2.0 * detail::max_radius(bed));
  const double* r = bed.radius.data();
  double worst = 0;
  cells.for_each_candidate([&](std::uint32_t i, std::uint32_t j, double d2) {
    const double sum = r[i] + r[j];
    if (d2 < sum * sum) worst = std::max(worst, (sum - std::sqrt(d2)) / sum);
  });
  return worst;
}

}  // namespace powderbed::bed
