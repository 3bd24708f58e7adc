#include "powderbed/keff/profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace powderbed::keff {

TemperatureProfile temperature_profile(const bed::Bed& bed, int axis,
                                       const std::vector<double>& temperature,
                                       const std::vector<std::uint32_t>& excluded,
                                       std::size_t bins) {
  const auto a = static_cast<std::size_t>(axis);
  const double lower = bed.domain.lower[a], height = bed.domain.length(axis);
  if (bins == 0) {
    const double mean_diameter =
        bed.n() ? 2 * std::accumulate(bed.radius.begin(), bed.radius.end(), 0.0) /
                      static_cast<double>(bed.n())
                : height;
    bins = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(height / mean_diameter)));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  TemperatureProfile p;
  p.position.resize(bins);
  p.mean.assign(bins, 0);
  p.min.assign(bins, std::numeric_limits<double>::infinity());
  p.max.assign(bins, -std::numeric_limits<double>::infinity());
  p.particles.assign(bins, 0);
  const double width = height / static_cast<double>(bins);
  for (std::size_t b = 0; b < bins; ++b)
    p.position[b] = lower + (static_cast<double>(b) + 0.5) * width;

  const std::vector<double>& centre = a == 0 ? bed.x : a == 1 ? bed.y : bed.z;
  auto next_excluded = excluded.begin();
  for (std::size_t i = 0; i < bed.n(); ++i) {
    if (next_excluded != excluded.end() && *next_excluded == i) {
      ++next_excluded;
      continue;
    }
    const double s = (centre[i] - lower) / width;
    const auto b = std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, s)));
    p.mean[b] += temperature[i];
    p.min[b] = std::min(p.min[b], temperature[i]);
    p.max[b] = std::max(p.max[b], temperature[i]);
    ++p.particles[b];
  }
  for (std::size_t b = 0; b < bins; ++b) {
    if (p.particles[b] == 0) {
      p.mean[b] = p.min[b] = p.max[b] = nan;
      continue;
    }
    p.mean[b] /= static_cast<double>(p.particles[b]);
  }
  return p;
}

}  // namespace powderbed::keff
