#include "powderbed/thermal/substrate.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "powderbed/bed/height_map.hpp"

namespace powderbed::thermal {

TopStencil top_stencil(const SubstrateGeometry& g, double x, double y) {
  // Across a periodic seam a position wraps into the period and row ny - 1 is row 0.
  if (g.periodic_y) y = bed::wrap_into(y, g.y0, g.period_y());
  const bed::GridCell c = bed::grid_cell(g.x0, g.dx, g.nx, g.y0, g.dy, g.ny, x, y);
  const std::size_t col = c.i + g.nx * c.j, up = g.canonical_column(col + g.nx);
  return TopStencil{{col, col + 1, up, up + 1},
                    {(1 - c.fx) * (1 - c.fy), c.fx * (1 - c.fy), (1 - c.fx) * c.fy, c.fx * c.fy}};
}

std::vector<std::pair<std::size_t, double>> top_footprint(const SubstrateGeometry& g, double x,
                                                          double y, double a) {
  std::vector<std::pair<std::size_t, double>> nodes;
  // The node indices within [v0, v1]: held on the grid along a bounded axis, unwrapped along a
  // periodic one, the disc then reaching across the seam.
  const auto range = [](double lo, double spacing, std::size_t count, bool periodic, double v0,
                        double v1) {
    double first = std::ceil((v0 - lo) / spacing), last = std::floor((v1 - lo) / spacing);
    if (!periodic) {
      first = std::clamp(first, 0.0, double(count - 1));
      last = std::clamp(last, 0.0, double(count - 1));
    }
    return std::pair{static_cast<long>(first), static_cast<long>(last)};
  };
  const auto [i0, i1] = range(g.x0, g.dx, g.nx, false, x - a, x + a);
  const auto [j0, j1] = range(g.y0, g.dy, g.ny, g.periodic_y, y - a, y + a);
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const double dx = g.x0 + g.dx * double(i) - x, dy = g.y0 + g.dy * double(j) - y;
      if (dx * dx + dy * dy > a * a) continue;
      const std::size_t row = g.periodic_y ? g.wrap_row(j) : static_cast<std::size_t>(j);
      nodes.push_back({static_cast<std::size_t>(i) + g.nx * row, 1.0});
    }
  if (nodes.empty()) {
    const TopStencil st = top_stencil(g, x, y);
    for (int w = 0; w < 4; ++w) nodes.push_back({st.column[w], st.weight[w]});
    return nodes;
  }
  for (auto& node : nodes) node.second = 1.0 / static_cast<double>(nodes.size());
  return nodes;
}

double top_height_at(const SubstrateGeometry& g, const TopHeight& top, double x, double y) {
  if (top.empty()) return g.z_top;
  const TopStencil st = top_stencil(g, x, y);
  double h = 0;
  for (int w = 0; w < 4; ++w) h += st.weight[w] * top[st.column[w]];
  return h;
}

bed::HeightMap top_surface(const SubstrateGeometry& g, const TopHeight& top) {
  bed::HeightMap m;
  if (top.empty()) return m;
  m.nx = g.nx;
  m.ny = g.ny;
  m.x0 = g.x0;
  m.y0 = g.y0;
  m.dx = g.dx;
  m.dy = g.dy;
  m.z = top;
  return m;
}

}  // namespace powderbed::thermal
