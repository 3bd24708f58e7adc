#include "powderbed/thermal/bed_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "powderbed/bed/stats.hpp"

namespace powderbed::thermal {

BedSurface analyse_surface(const bed::Bed& bed, double substrate_top) {
  const std::size_t n = bed.n();
  BedSurface s;
  s.exposed.assign(n, 0);
  s.depth.assign(n, 0.0);
  if (n == 0) return s;

  double r_min = std::numeric_limits<double>::infinity(), diameter_sum = 0;
  std::vector<double> tops(n);
  for (std::size_t i = 0; i < n; ++i) {
    r_min = std::min(r_min, bed.radius[i]);
    diameter_sum += 2 * bed.radius[i];
    tops[i] = bed.z[i] + bed.radius[i] - substrate_top;
  }
  s.mean_diameter = diameter_sum / static_cast<double>(n);
  std::nth_element(tops.begin(), tops.begin() + static_cast<std::ptrdiff_t>(n / 2), tops.end());
  s.layer_height = tops[n / 2];
  const double z_top = substrate_top + s.layer_height;
  s.porosity = 1 - bed::layer_density(bed, substrate_top, z_top);

  const double x0 = bed.domain.lower[0], y0 = bed.domain.lower[1];
  const double lx = bed.domain.length(0), ly = bed.domain.length(1);
  double h = std::min(0.5 * r_min, s.mean_diameter / 8);
  h = std::max(h, std::sqrt(lx * ly / 4e6));
  s.sample_spacing = h;
  const auto nx = static_cast<std::size_t>(std::ceil(lx / h)) + 1;
  const auto ny = static_cast<std::size_t>(std::ceil(ly / h)) + 1;
  const double lowest = -std::numeric_limits<double>::infinity();
  std::vector<double> height(nx * ny, lowest);
  std::vector<std::uint32_t> owner(nx * ny, std::numeric_limits<std::uint32_t>::max());
  const auto clamp_index = [](double v, std::size_t count) {
    return static_cast<std::size_t>(std::clamp(v, 0.0, static_cast<double>(count - 1)));
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double r = bed.radius[i];
    const std::size_t i0 = clamp_index(std::ceil((bed.x[i] - r - x0) / h), nx);
    const std::size_t i1 = clamp_index(std::floor((bed.x[i] + r - x0) / h), nx);
    const std::size_t j0 = clamp_index(std::ceil((bed.y[i] - r - y0) / h), ny);
    const std::size_t j1 = clamp_index(std::floor((bed.y[i] + r - y0) / h), ny);
    for (std::size_t j = j0; j <= j1; ++j) {
      const double dy = y0 + h * static_cast<double>(j) - bed.y[i];
      for (std::size_t k = i0; k <= i1; ++k) {
        const double dx = x0 + h * static_cast<double>(k) - bed.x[i];
        const double d2 = dx * dx + dy * dy;
        if (d2 > r * r) continue;
        const double top = bed.z[i] + std::sqrt(r * r - d2);
        if (top > height[j * nx + k]) {
          height[j * nx + k] = top;
          owner[j * nx + k] = static_cast<std::uint32_t>(i);
        }
      }
    }
  }
  for (const auto o : owner)
    if (o < n) s.exposed[o] = 1;
  s.samples_x = nx;
  s.samples_y = ny;
  s.x0 = x0;
  s.y0 = y0;
  s.column.resize(nx * ny);
  for (std::size_t k = 0; k < nx * ny; ++k)
    s.column[k] = height[k] == lowest ? 0.0 : std::max(0.0, height[k] - substrate_top);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = clamp_index(std::round((bed.x[i] - x0) / h), nx);
    const std::size_t j = clamp_index(std::round((bed.y[i] - y0) / h), ny);
    const double surface = height[j * nx + k];
    s.depth[i] = std::max(0.0, surface - (bed.z[i] + bed.radius[i]));
    if (s.depth[i] == 0) s.exposed[i] = 1;
  }
  return s;
}

double BedSurface::column_height(double x, double y) const {
  if (column.empty()) return 0;
  const double fx = std::round((x - x0) / sample_spacing);
  const double fy = std::round((y - y0) / sample_spacing);
  if (fx < 0 || fy < 0 || fx >= static_cast<double>(samples_x) ||
      fy >= static_cast<double>(samples_y))
    return 0;
  return column[static_cast<std::size_t>(fy) * samples_x + static_cast<std::size_t>(fx)];
}

}  // namespace powderbed::thermal
