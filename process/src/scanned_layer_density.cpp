#include "powderbed/process/scanned_layer_density.hpp"

#include <algorithm>
#include <cmath>

#include "powderbed/bed/sphere_volume.hpp"

namespace powderbed::process {

double scanned_layer_density(const bed::Bed& bed, const thermal::SubstrateGeometry& g,
                             const thermal::TopHeight& top, const thermal::LackOfFusion& lof,
                             double bottom) {
  double space = 0, solid = 0;
  for (std::size_t c = 0; c < lof.map.size(); ++c)
    if (lof.map[c] != thermal::kNotScanned)
      space += g.dx * g.dy * std::max(0.0, bottom - (top.empty() ? g.z_top : top[c]));
  const auto column = [](double v, double v0, double d, std::size_t n) {
    return static_cast<std::size_t>(std::clamp(std::lround((v - v0) / d), 0L, static_cast<long>(n - 1)));
  };
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const std::size_t c = column(bed.x[i], g.x0, g.dx, g.nx) + g.nx * column(bed.y[i], g.y0, g.dy, g.ny);
    if (lof.map[c] == thermal::kNotScanned || bed.z[i] >= bottom) continue;
    solid += bed::sphere_volume(bed.radius[i]);
  }
  return space > 0 ? solid / space : 0.0;
}

}  // namespace powderbed::process
