// k_core from the least-squares line through the core particles (core_conductivity.hpp).
#include "powderbed/keff/core_conductivity.hpp"

#include <cmath>
#include <limits>
#include <numeric>

namespace powderbed::keff {

CoreConductivity core_conductivity(const bed::Bed& bed, int axis,
                                   const std::vector<double>& temperature,
                                   const std::vector<std::uint32_t>& excluded, double flux,
                                   double t_hot, double t_cold, double margin) {
  const auto a = static_cast<std::size_t>(axis);
  const double lower = bed.domain.lower[a], upper = bed.domain.upper[a];
  CoreConductivity c;
  c.k_core = std::numeric_limits<double>::quiet_NaN();
  if (margin < 0) {
    const double mean_radius =
        bed.n() ? std::accumulate(bed.radius.begin(), bed.radius.end(), 0.0) /
                      static_cast<double>(bed.n())
                : 0.0;
    margin = 4 * mean_radius;  // two mean diameters
  }
  c.margin = margin;
  const std::vector<double>& centre = a == 0 ? bed.x : a == 1 ? bed.y : bed.z;
  // Sums about the box's middle, so the normal equations do not lose digits to a far origin.
  const double mid = (lower + upper) / 2;
  double n = 0, sx = 0, st = 0, sxx = 0, sxt = 0;
  auto next_excluded = excluded.begin();
  for (std::size_t i = 0; i < bed.n(); ++i) {
    if (next_excluded != excluded.end() && *next_excluded == i) {
      ++next_excluded;
      continue;
    }
    if (!(centre[i] > lower + margin && centre[i] < upper - margin)) continue;
    const double x = centre[i] - mid, t = temperature[i];
    n += 1;
    sx += x;
    st += t;
    sxx += x * x;
    sxt += x * t;
  }
  c.particles = static_cast<std::size_t>(n);
  const double spread = sxx - sx * sx / n;
  if (n < 2 || !(spread > 0)) return c;
  c.gradient = (sxt - sx * st / n) / spread;
  const double at_mid = st / n - c.gradient * sx / n;
  const double span = t_hot - t_cold;
  c.drop_hot = (t_hot - (at_mid + c.gradient * (upper - mid))) / span;
  c.drop_cold = ((at_mid + c.gradient * (lower - mid)) - t_cold) / span;
  c.k_core = flux / c.gradient;
  return c;
}

}  // namespace powderbed::keff
