#include "powderbed/thermal/melt_pool.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace powderbed::thermal {

double crossing(double peak_a, double peak_b, double t_m) {
  if (peak_a <= peak_b) return 0;
  return std::clamp((peak_a - t_m) / (peak_a - peak_b), 0.0, 1.0);
}

MeltPool measure_melt_pool(const MeltPoolInput& in) {
  const SubstrateGeometry& g = *in.grid;
  const auto& peak = *in.node_peak;
  const double t_m = in.melting_point;
  const auto i = static_cast<std::size_t>(
      std::clamp(std::round((in.x_plane - g.x0) / g.dx), 0.0, static_cast<double>(g.nx - 1)));
  MeltPool pool;
  double y_lo = std::numeric_limits<double>::infinity(), y_hi = -y_lo;
  const auto top_at = [&](std::size_t j) { return g.index(i, j, (*in.top_plane)[i + g.nx * j]); };
  for (std::size_t j = 0; j < g.ny; ++j) {
    if (peak[top_at(j)] < t_m) continue;
    std::size_t k = (*in.top_plane)[i + g.nx * j];
    while (k > 0 && peak[g.index(i, j, k - 1)] >= t_m) --k;
    double depth = g.z_top - g.z(k);
    if (k > 0) depth += g.dz * crossing(peak[g.index(i, j, k)], peak[g.index(i, j, k - 1)], t_m);
    pool.depth = std::max(pool.depth, depth);
    double lo = g.y(j), hi = g.y(j);
    if (j > 0 && peak[top_at(j - 1)] < t_m)
      lo -= g.dy * crossing(peak[top_at(j)], peak[top_at(j - 1)], t_m);
    if (j + 1 < g.ny && peak[top_at(j + 1)] < t_m)
      hi += g.dy * crossing(peak[top_at(j)], peak[top_at(j + 1)], t_m);
    y_lo = std::min(y_lo, lo);
    y_hi = std::max(y_hi, hi);
  }
  const auto& x = *in.x;
  for (std::size_t p = 0; p < x.size(); ++p) {
    const double r = (*in.radius)[p], dx = x[p] - in.x_plane;
    if ((*in.particle_peak)[p] < t_m || std::abs(dx) >= r) continue;
    const double cut = std::sqrt(r * r - dx * dx);
    pool.height = std::max(pool.height, (*in.z)[p] + cut - g.z_top);
    y_lo = std::min(y_lo, (*in.y)[p] - cut);
    y_hi = std::max(y_hi, (*in.y)[p] + cut);
  }
  if (y_hi > y_lo) pool.width = y_hi - y_lo;
  return pool;
}

MeltPool measure_section(const SectionInput& in) {
  const SubstrateGeometry& g = *in.grid;
  const auto& peak = *in.peak;
  const auto& across = *in.across;
  const double t_m = in.melting_point;
  const std::size_t nz = g.nz, samples = across.size();
  const auto at = [&](std::size_t q, std::size_t k) { return peak[q * nz + k]; };
  // Sample q's top node (its column's top plane).
  const auto top = [&](std::size_t q) {
    return static_cast<std::size_t>((*in.top_plane)[(*in.columns)[q]]);
  };
  MeltPool pool;
  double s_lo = std::numeric_limits<double>::infinity(), s_hi = -s_lo;
  for (std::size_t q = 0; q < samples; ++q) {
    if (at(q, top(q)) < t_m) continue;
    std::size_t k = top(q);
    while (k > 0 && at(q, k - 1) >= t_m) --k;
    double depth = g.z_top - g.z(k);
    if (k > 0) depth += g.dz * crossing(at(q, k), at(q, k - 1), t_m);
    if (!in.top->empty()) depth += (*in.top)[(*in.columns)[q]] - g.z_top;
    pool.depth = std::max(pool.depth, depth);
    double lo = across[q], hi = across[q];
    if (q > 0 && at(q - 1, top(q - 1)) < t_m)
      lo -= (across[q] - across[q - 1]) * crossing(at(q, top(q)), at(q - 1, top(q - 1)), t_m);
    if (q + 1 < samples && at(q + 1, top(q + 1)) < t_m)
      hi += (across[q + 1] - across[q]) * crossing(at(q, top(q)), at(q + 1, top(q + 1)), t_m);
    s_lo = std::min(s_lo, lo);
    s_hi = std::max(s_hi, hi);
  }
  const auto& x = *in.x;
  const double period = g.period_y();
  for (std::size_t p = 0; p < x.size(); ++p) {
    const double r = (*in.radius)[p];
    const double ox = x[p] - in.cx;
    double oy = (*in.y)[p] - in.cy;
    if (g.periodic_y) oy -= period * std::round(oy / period);  // seen from the track, as the probe
    const double off = ox * in.dx + oy * in.dy;  // from the plane
    if ((*in.particle_peak)[p] < t_m || std::abs(off) >= r) continue;
    const double cut = std::sqrt(r * r - off * off), along = -ox * in.dy + oy * in.dx;
    // Beyond the section's ends (a periodic plate's: section_reach) it is another pool's.
    if (samples > 0 && (along + cut < across.front() || along - cut > across.back())) continue;
    pool.height = std::max(pool.height, (*in.z)[p] + cut - g.z_top);
    s_lo = std::min(s_lo, along - cut);
    s_hi = std::max(s_hi, along + cut);
  }
  if (s_hi > s_lo) pool.width = s_hi - s_lo;
  return pool;
}

}  // namespace powderbed::thermal
