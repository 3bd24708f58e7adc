#pragma once
// A surface z = h(x, y) given at the nodes of a regular grid (x0 + i dx, y0 + j dy), bilinear
// between them and held at the edge value beyond the grid: the fused solid's top, which sinter
// raises (thermal/fusion.hpp) and the next layer's powder is spread on (dem/spread.hpp). One
// interpolation for both, so the powder rests on the surface the thermal grid conducts through.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace powderbed::bed {

// The grid cell around (x, y): its lower node (i, j) and the fractions (fx, fy) in [0, 1] across
// it; positions beyond the grid are clamped onto its edge.
struct GridCell {
  std::size_t i = 0, j = 0;
  double fx = 0, fy = 0;
};

inline GridCell grid_cell(double x0, double dx, std::size_t nx, double y0, double dy,
                          std::size_t ny, double x, double y) {
  const double ux = std::clamp((x - x0) / dx, 0.0, static_cast<double>(nx - 1));
  const double uy = std::clamp((y - y0) / dy, 0.0, static_cast<double>(ny - 1));
  GridCell c;
  c.i = std::min(static_cast<std::size_t>(ux), nx - 2);
  c.j = std::min(static_cast<std::size_t>(uy), ny - 2);
  c.fx = ux - static_cast<double>(c.i);
  c.fy = uy - static_cast<double>(c.j);
  return c;
}

struct HeightMap {
  std::size_t nx = 0, ny = 0;  // nodes along x and y (>= 2 each when not empty)
  double x0 = 0, y0 = 0, dx = 0, dy = 0;
  std::vector<double> z;       // per node i + nx j, m

  bool empty() const { return z.empty(); }
  GridCell cell(double x, double y) const { return grid_cell(x0, dx, nx, y0, dy, ny, x, y); }
  double node(std::size_t i, std::size_t j) const { return z[i + nx * j]; }

  // h(x, y), bilinear in the four nodes around (x, y).
  double at(double x, double y) const {
    const GridCell c = cell(x, y);
    return (1 - c.fy) * ((1 - c.fx) * node(c.i, c.j) + c.fx * node(c.i + 1, c.j)) +
           c.fy * ((1 - c.fx) * node(c.i, c.j + 1) + c.fx * node(c.i + 1, c.j + 1));
  }
  // (dh/dx, dh/dy) of the bilinear patch at (x, y) (zero across a clamped edge).
  std::array<double, 2> slope(double x, double y) const {
    const GridCell c = cell(x, y);
    const double ux = (x - x0) / dx, uy = (y - y0) / dy;
    const bool inside_x = ux > 0 && ux < static_cast<double>(nx - 1);
    const bool inside_y = uy > 0 && uy < static_cast<double>(ny - 1);
    const double sx = ((1 - c.fy) * (node(c.i + 1, c.j) - node(c.i, c.j)) +
                       c.fy * (node(c.i + 1, c.j + 1) - node(c.i, c.j + 1))) / dx;
    const double sy = ((1 - c.fx) * (node(c.i, c.j + 1) - node(c.i, c.j)) +
                       c.fx * (node(c.i + 1, c.j + 1) - node(c.i + 1, c.j))) / dy;
    return {inside_x ? sx : 0.0, inside_y ? sy : 0.0};
  }
  // A surface over a box periodic along x or y has one edge line, not two: the nodes of the two
  // edge rows (columns) take their mean, which keeps their sum, so the volume under the surface
  // (each node owning dx dy) is unchanged. A sphere crossing the seam then finds the surface it
  // left, instead of a step it would be deep inside.
  void join_periodic_edges(bool periodic_x, bool periodic_y) {
    if (empty()) return;
    if (periodic_y)
      for (std::size_t i = 0; i < nx; ++i) {
        double& a = z[i];
        double& b = z[i + nx * (ny - 1)];
        a = b = 0.5 * (a + b);
      }
    if (periodic_x)
      for (std::size_t j = 0; j < ny; ++j) {
        double& a = z[nx * j];
        double& b = z[nx - 1 + nx * j];
        a = b = 0.5 * (a + b);
      }
  }
  double highest() const { return empty() ? 0.0 : *std::max_element(z.begin(), z.end()); }

  // The surface point nearest a sphere's centre (x, y, z) of radius r, sampled at the centre's
  // foot and on rings of 0.35 r, 0.7 r and r around it (8 points each): a fused top is steep
  // (a particle's volume raised over its footprint), so the surface right under the centre can
  // be far lower than a step beside it that the sphere already touches. `offset` points from the
  // centre to that point; offset[2] >= 0 when the centre is at or below the surface.
  struct Nearest {
    double offset[3];
    double distance;
  };
  // cos and sin of the rings' 8 directions 2πk/8, computed once: the spread asks for the
  // nearest point of every particle near the floor at every step.
  static const std::array<std::array<double, 2>, 8>& ring_directions() {
    static const std::array<std::array<double, 2>, 8> directions = [] {
      std::array<std::array<double, 2>, 8> d{};
      for (int k = 0; k < 8; ++k) {
        const double a = 2 * std::numbers::pi * k / 8;
        d[k] = {std::cos(a), std::sin(a)};
      }
      return d;
    }();
    return directions;
  }
  Nearest nearest(double x, double y, double zc, double r) const {
    const double foot = at(x, y) - zc;
    Nearest best{{0, 0, foot}, std::abs(foot)};
    if (foot >= 0) return best;
    const auto& directions = ring_directions();
    for (const double ring : {0.35, 0.7, 1.0}) {
      // A point on this ring (and the larger ones) lies at least ring r from the centre: none
      // can be nearer than the best found once that is no more than ring r.
      if (ring * r >= best.distance) break;
      for (const auto& [c, s] : directions) {
        const double ex = ring * r * c, ey = ring * r * s;
        const double ez = at(x + ex, y + ey) - zc;
        const double d = std::sqrt(ex * ex + ey * ey + ez * ez);
        if (d < best.distance) best = {{ex, ey, ez}, d};
      }
    }
    return best;
  }
  // How deep a sphere reaches into the surface: r less its distance to the nearest point, or r
  // plus the depth of its centre below the surface (<= 0: clear of it).
  double overlap(double x, double y, double zc, double r) const {
    const Nearest p = nearest(x, y, zc, r);
    return p.offset[2] >= 0 ? r + p.offset[2] : r - p.distance;
  }
};

}  // namespace powderbed::bed
