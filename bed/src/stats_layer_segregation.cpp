// Size segregation along the spreading direction (docs/spread-layer.md "Segregation"): the mean
// diameter of the layer particles in equal x bins, and the slope of the least-squares line of
// diameter against x over the particles, b = sum (x_i - xbar)(d_i - dbar) / sum (x_i - xbar)^2.
// A recoater that carries the large particles ahead leaves b > 0 along its path.
#include <algorithm>
#include <cmath>
#include <limits>

#include "powderbed/bed/stats_layer.hpp"

namespace powderbed::bed {

Segregation size_segregation(const std::vector<double>& x, const std::vector<double>& d,
                             double x0, double x1, std::size_t bins) {
  Segregation s;
  const double width = (x1 - x0) / static_cast<double>(bins);
  s.x.resize(bins);
  for (std::size_t k = 0; k < bins; ++k) s.x[k] = x0 + (static_cast<double>(k) + 0.5) * width;
  std::vector<double> sum(bins, 0.0);
  s.count.assign(bins, 0);
  const double last = static_cast<double>(bins - 1);
  double xbar = 0, dbar = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto k = static_cast<std::size_t>(std::clamp(std::floor((x[i] - x0) / width), 0.0, last));
    sum[k] += d[i];
    ++s.count[k];
    xbar += x[i];
    dbar += d[i];
  }
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  s.mean_diameter.resize(bins);
  for (std::size_t k = 0; k < bins; ++k) {
    s.mean_diameter[k] = s.count[k] ? sum[k] / static_cast<double>(s.count[k]) : nan;
  }
  s.slope = nan;
  if (x.size() < 2) return s;
  xbar /= static_cast<double>(x.size());
  dbar /= static_cast<double>(x.size());
  double sxd = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxd += (x[i] - xbar) * (d[i] - dbar);
    sxx += (x[i] - xbar) * (x[i] - xbar);
  }
  if (sxx > 0) s.slope = sxd / sxx;
  return s;
}

}  // namespace powderbed::bed
