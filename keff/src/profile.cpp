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

double profile_r_squared(const TemperatureProfile& profile) {
  std::vector<double> x, t;
  for (std::size_t b = 0; b < profile.position.size(); ++b)
    if (profile.particles[b] > 0) {
      x.push_back(profile.position[b]);
      t.push_back(profile.mean[b]);
    }
  const double n = static_cast<double>(x.size());
  if (x.size() < 3) return std::numeric_limits<double>::quiet_NaN();
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n;
  const double mt = std::accumulate(t.begin(), t.end(), 0.0) / n;
  double sxx = 0, sxt = 0, stt = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxx += (x[k] - mx) * (x[k] - mx);
    sxt += (x[k] - mx) * (t[k] - mt);
    stt += (t[k] - mt) * (t[k] - mt);
  }
  if (!(stt > 0)) return 1;  // a flat profile is its own line
  return sxt * sxt / (sxx * stt);  // 1 − SS_res / SS_tot for a least-squares line
}

}  // namespace powderbed::keff
