// Contact statistics of docs/physics.md §2: coordination number, contacts per particle, rattlers, wall
// contacts, and the largest relative overlap.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "neighbours_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/stats.hpp"

namespace powderbed::bed {

// docs/physics.md §2: a pair touches when d_ij <= (r_i + r_j)(1 + tol); Z = 2 contacts / N. A particle
// touches a non-periodic face when its centre is within r (1 + tol) of it (2D: x and y faces).
// All tolerances are counted in one pass over the cell list built for the largest of them.
std::vector<ContactStats> contact_stats(const Bed& bed, const std::vector<double>& tolerances) {
  for (const double tolerance : tolerances) {
    if (!std::isfinite(tolerance) || !(tolerance > -1)) {
      throw InputError(
          fmt::format("contact_stats: tolerance {:g} (accepted: finite, > -1)", tolerance));
    }
  }
  detail::check_pair_index_range(bed, "contact_stats");
  const std::size_t nt = tolerances.size();
  std::vector<ContactStats> out(nt);
  for (std::size_t t = 0; t < nt; ++t) out[t].tolerance = tolerances[t];
  const std::size_t n = bed.n();
  if (n == 0 || nt == 0) return out;
  std::vector<double> scale(nt);
  for (std::size_t t = 0; t < nt; ++t) scale[t] = 1.0 + tolerances[t];
  const double widest = *std::max_element(scale.begin(), scale.end());
  std::vector<std::uint32_t> per_particle(n * nt, 0);  // [particle][tolerance]
  std::vector<std::size_t> contacts(nt, 0);
  if (n > 1) {
    const detail::PairGeometry geometry(bed);
    const detail::CellList cells(geometry, 2.0 * detail::max_radius(bed) * std::max(widest, 1.0));
    const double* r = bed.radius.data();
    cells.for_each_candidate([&](std::uint32_t i, std::uint32_t j, double d2) {
      const double sum = r[i] + r[j];
      const double far = sum * widest;
      // Cheap squared pre-test (widened past rounding), then the exact rule on d itself.
      if (d2 > far * far * (1.0 + 1e-12)) return;
      const double d = std::sqrt(d2);
      for (std::size_t t = 0; t < nt; ++t) {
        if (d <= sum * scale[t]) {
          ++per_particle[i * nt + t];
          ++per_particle[j * nt + t];
          ++contacts[t];
        }
      }
    });
  }
  const Domain& dom = bed.domain;
  const std::vector<double>* centre[3] = {&bed.x, &bed.y, &bed.z};
  for (std::size_t t = 0; t < nt; ++t) {
    ContactStats& o = out[t];
    o.contacts = contacts[t];
    o.coordination = 2.0 * static_cast<double>(contacts[t]) / static_cast<double>(n);
    std::uint32_t most = 0;
    for (std::size_t i = 0; i < n; ++i) most = std::max(most, per_particle[i * nt + t]);
    o.histogram.assign(std::size_t{most} + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++o.histogram[per_particle[i * nt + t]];
    // A rattler touches nothing: a particle with no particle contact that rests on the floor or
    // leans on a wall is held (docs/physics.md §2), so it is not one.
    for (std::size_t i = 0; i < n; ++i) {
      const double reach = bed.radius[i] * scale[t];
      bool held = per_particle[i * nt + t] > 0;
      for (int a = 0; a < dom.dimension; ++a) {
        if (dom.periodic[a]) continue;
        const double c = (*centre[a])[i];
        const int touches = (c - dom.lower[a] <= reach) + (dom.upper[a] - c <= reach);
        o.wall_contacts += touches;
        held = held || touches > 0;
      }
      if (!held) ++o.rattlers;
    }
  }
  return out;
}

ContactStats contact_stats(const Bed& bed, double tolerance) {
  return contact_stats(bed, std::vector<double>{tolerance}).front();
}

// docs/physics.md §2 overlap check: max over pairs of (r_i + r_j - d) / (r_i + r_j).
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
