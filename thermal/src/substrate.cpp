#include "powderbed/thermal/substrate.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "powderbed/bed/height_map.hpp"

namespace powderbed::thermal {

TopStencil top_stencil(const SubstrateGeometry& g, double x, double y) {
  const bed::GridCell c = bed::grid_cell(g.x0, g.dx, g.nx, g.y0, g.dy, g.ny, x, y);
  const std::size_t col = c.i + g.nx * c.j;
  return TopStencil{{col, col + 1, col + g.nx, col + g.nx + 1},
                    {(1 - c.fx) * (1 - c.fy), c.fx * (1 - c.fy), (1 - c.fx) * c.fy, c.fx * c.fy}};
}

std::vector<std::pair<std::size_t, double>> top_footprint(const SubstrateGeometry& g, double x,
                                                          double y, double a) {
  std::vector<std::pair<std::size_t, double>> nodes;
  const auto range = [](double lo, double spacing, std::size_t count, double v0, double v1) {
    const double first = std::clamp(std::ceil((v0 - lo) / spacing), 0.0, double(count - 1));
    const double last = std::clamp(std::floor((v1 - lo) / spacing), 0.0, double(count - 1));
    return std::pair{static_cast<std::size_t>(first), static_cast<std::size_t>(last)};
  };
  const auto [i0, i1] = range(g.x0, g.dx, g.nx, x - a, x + a);
  const auto [j0, j1] = range(g.y0, g.dy, g.ny, y - a, y + a);
  for (std::size_t j = j0; j <= j1; ++j)
    for (std::size_t i = i0; i <= i1; ++i) {
      const double dx = g.x(i) - x, dy = g.y(j) - y;
      if (dx * dx + dy * dy <= a * a) nodes.push_back({i + g.nx * j, 1.0});
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
