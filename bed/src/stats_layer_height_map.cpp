// The top view of a spread layer (docs/spread-layer.md "Height map"): the surface height
// h(x, y) = max_i [z_i + sqrt(r_i^2 - rho_i^2)] - plate at each cell centre, rho_i the horizontal
// distance to sphere i, over the spheres that reach into the layer (z_i - r_i < top and
// z_i + r_i > plate); 0 over bare plate. A profilometer's reading of the powder, sampled at the
// cell centres, so that Sa, Sq and the coverage converge to their continuous values as the cell
// shrinks (the midpoint rule of the area integrals).
#include <algorithm>
#include <cmath>

#include "powderbed/bed/stats_layer.hpp"

namespace powderbed::bed {

namespace {

// Image shifts (m) of a sphere along a periodic axis that can reach [lo, hi]; none but 0 when
// the axis is not periodic.
std::vector<double> image_shifts(const Domain& d, int axis, double c, double r, double lo,
                                 double hi) {
  if (!d.periodic[axis]) return {0.0};
  const double period = d.length(axis);
  std::vector<double> out;
  const double k0 = std::ceil((lo - c - r) / period), k1 = std::floor((hi - c + r) / period);
  for (double k = k0; k <= k1; k += 1.0) out.push_back(k * period);
  return out;
}

// First and last cell index (inclusive) whose centre lies within r of c; first > last if none.
std::pair<long, long> cell_span(double c, double r, double lo, double step, std::size_t cells) {
  const long first = std::max(0L, static_cast<long>(std::ceil((c - r - lo) / step - 0.5)));
  const long last = std::min(static_cast<long>(cells) - 1,
                             static_cast<long>(std::floor((c + r - lo) / step - 0.5)));
  return {first, last};
}

}  // namespace

LayerHeightMap height_map(const Bed& bed, const LayerRequest& q) {
  const Domain& d = bed.domain;
  LayerHeightMap m;
  m.x0 = q.x0;
  m.y0 = d.lower[1];
  m.nx = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround((q.x1 - q.x0) / q.raster)));
  m.ny = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(d.length(1) / q.raster)));
  m.dx = (q.x1 - q.x0) / static_cast<double>(m.nx);
  m.dy = d.length(1) / static_cast<double>(m.ny);
  m.height.assign(m.nx * m.ny, 0.0);
  m.covered.assign(m.nx * m.ny, 0);
  const double top = q.plate + q.gap;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double r = bed.radius[i], zc = bed.z[i];
    if (!(zc - r < top && zc + r > q.plate)) continue;
    for (const double sx : image_shifts(d, 0, bed.x[i], r, q.x0, q.x1)) {
      for (const double sy : image_shifts(d, 1, bed.y[i], r, d.lower[1], d.upper[1])) {
        const double cx = bed.x[i] + sx, cy = bed.y[i] + sy;
        const auto [ix0, ix1] = cell_span(cx, r, m.x0, m.dx, m.nx);
        const auto [iy0, iy1] = cell_span(cy, r, m.y0, m.dy, m.ny);
        for (long iy = iy0; iy <= iy1; ++iy) {
          const double py = m.y0 + (static_cast<double>(iy) + 0.5) * m.dy - cy;
          for (long ix = ix0; ix <= ix1; ++ix) {
            const double px = m.x0 + (static_cast<double>(ix) + 0.5) * m.dx - cx;
            const double rho2 = px * px + py * py;
            if (rho2 >= r * r) continue;
            const double h = zc + std::sqrt(r * r - rho2) - q.plate;
            if (h <= 0) continue;  // the sphere passes below the plate here
            const std::size_t k = static_cast<std::size_t>(iy) * m.nx + static_cast<std::size_t>(ix);
            m.height[k] = std::max(m.height[k], h);
            m.covered[k] = 1;
          }
        }
      }
    }
  }
  return m;
}

}  // namespace powderbed::bed
