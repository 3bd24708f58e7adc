#include "powderbed/thermal/lack_of_fusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "powderbed/bed/errors.hpp"
#include "powderbed/thermal/melt_pool.hpp"

namespace powderbed::thermal {

namespace {

// Whether (x, y) lies within `half_width` of the segment, measured across it, between its ends.
bool within_strip(const ScanSegment& s, double half_width, double x, double y) {
  const double ex = s.x1 - s.x0, ey = s.y1 - s.y0, length = std::hypot(ex, ey);
  const double along = ((x - s.x0) * ex + (y - s.y0) * ey) / length;
  const double across = std::abs((y - s.y0) * ex - (x - s.x0) * ey) / length;
  return along >= 0 && along <= length && across <= half_width;
}

}  // namespace

double molten_bottom(const SubstrateGeometry& g, const std::vector<double>& peak,
                     std::size_t column, std::size_t top_plane, double threshold) {
  const auto at = [&](std::size_t k) { return peak[g.node(column, k)]; };
  if (at(top_plane) < threshold) return std::numeric_limits<double>::infinity();
  std::size_t k = top_plane;
  while (k > 1 && at(k - 1) >= threshold) --k;
  return g.z(k) - g.dz * crossing(at(k), at(k - 1), threshold);
}

double LackOfFusion::mean_remelt() const {
  double sum = 0;
  for (const double d : remelt) sum += d;
  return remelt.empty() ? 0.0 : sum / static_cast<double>(remelt.size());
}

double LackOfFusion::min_remelt() const {
  return remelt.empty() ? 0.0 : *std::min_element(remelt.begin(), remelt.end());
}

LackOfFusion lack_of_fusion(const Sinter& sinter, double half_width, double threshold,
                            const TopHeight& start) {
  require_in_range(half_width > 0 && std::isfinite(half_width), "lack-of-fusion half width",
                   half_width, "a half width > 0 m");
  const SubstrateGeometry& g = sinter.grid();
  const auto& peak = sinter.substrate_peak();
  const auto& plane = sinter.top_planes();
  const std::vector<ScanSegment>& path = sinter.scan_path();
  LackOfFusion out;
  out.threshold = threshold;
  out.half_width = half_width;
  out.map.assign(g.nx * g.ny, kNotScanned);
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const bool scanned = std::any_of(path.begin(), path.end(), [&](const ScanSegment& s) {
        return s.length() > 0 && within_strip(s, half_width, g.x(i), g.y(j));
      });
      const std::size_t column = i + g.nx * j;
      if (!scanned || g.image_column(column)) continue;  // an image is counted as its row 0
      const bool bonded = peak[g.node(column, plane[column])] >= threshold;
      out.map[i + g.nx * j] = bonded ? kBonded : kUnbonded;
      const double top = start.empty() ? g.z_top : start[column];
      const double bottom = molten_bottom(g, peak, column, plane[column], threshold);
      out.remelt.push_back(std::isfinite(bottom) ? std::max(0.0, top - bottom) : 0.0);
      ++out.scanned;
      out.unbonded += bonded ? 0 : 1;
    }
  return out;
}

double bonded_width(const LackOfFusion& lof, const SubstrateGeometry& g, double x_plane) {
  const auto i = static_cast<std::size_t>(
      std::clamp(std::lround((x_plane - g.x0) / g.dx), 0L, static_cast<long>(g.nx - 1)));
  std::size_t bonded = 0;
  for (std::size_t j = 0; j < g.ny; ++j) bonded += lof.map[i + g.nx * j] == kBonded ? 1 : 0;  // images: kNotScanned
  return static_cast<double>(bonded) * g.dy;
}

}  // namespace powderbed::thermal
