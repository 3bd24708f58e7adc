#include "powderbed/thermal/substrate.hpp"

#include <algorithm>
#include <cmath>

namespace powderbed::thermal {

TopStencil top_stencil(const SubstrateGeometry& g, double x, double y) {
  const double fx_all = std::clamp((x - g.x0) / g.dx, 0.0, static_cast<double>(g.nx - 1));
  const double fy_all = std::clamp((y - g.y0) / g.dy, 0.0, static_cast<double>(g.ny - 1));
  const auto i = std::min(static_cast<std::size_t>(fx_all), g.nx - 2);
  const auto j = std::min(static_cast<std::size_t>(fy_all), g.ny - 2);
  const double fx = fx_all - static_cast<double>(i), fy = fy_all - static_cast<double>(j);
  const std::size_t k = g.nz - 1;
  return TopStencil{{g.index(i, j, k), g.index(i + 1, j, k), g.index(i, j + 1, k),
                     g.index(i + 1, j + 1, k)},
                    {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy}};
}

}  // namespace powderbed::thermal
