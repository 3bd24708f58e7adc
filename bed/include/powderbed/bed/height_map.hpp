#pragma once
// A surface z = h(x, y) given at the nodes of a regular grid (x0 + i dx, y0 + j dy), bilinear
// between them and held at the edge value beyond the grid, or repeated along an axis the grid
// spans as a period (periodic_x, periodic_y): the fused solid's top, which sinter
// raises (thermal/fusion.hpp) and the next layer's powder is spread on (dem/spread.hpp). The
// thermal grid conducts through the bilinear surface; spheres touch the same nodes cut into
// triangles (surface()), on which the nearest point is exact.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "powderbed/bed/closest_point_triangle.hpp"

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

// Wrapped into [lo, lo + period): where a position on a periodic axis lies in the period.
inline double wrap_into(double v, double lo, double period) {
  const double u = v - lo - period * std::floor((v - lo) / period);
  return lo + (u < period ? u : 0.0);  // u rounds up to the period for v just below lo
}

struct HeightMap {
  std::size_t nx = 0, ny = 0;  // nodes along x and y (>= 2 each when not empty)
  double x0 = 0, y0 = 0, dx = 0, dy = 0;
  std::vector<double> z;       // per node i + nx j, m
  // Along a periodic axis the grid spans the box's period: its last node row is its first
  // (join_periodic_edges makes them equal), a position wraps into the period instead of being
  // held at the edge, and a sphere over the seam touches the surface on both sides of it (a
  // surface held flat beyond the seam would change under a sphere the moment it crosses it,
  // and the jump in overlap throws it off: docs/build.md "Limits").
  bool periodic_x = false, periodic_y = false;

  bool empty() const { return z.empty(); }
  double period_x() const { return dx * static_cast<double>(nx - 1); }
  double period_y() const { return dy * static_cast<double>(ny - 1); }
  // Whether the nodes run from `lower` to `lower + length` along axis 0 (x) or 1 (y), to a
  // thousandth of a spacing: whether the grid can be periodic over a box that long there.
  bool spans(int axis, double lower, double length) const {
    const double start = axis == 0 ? x0 : y0, d = axis == 0 ? dx : dy;
    const double extent = axis == 0 ? period_x() : period_y();
    return std::abs(start - lower) < 1e-3 * d && std::abs(extent - length) < 1e-3 * d;
  }
  GridCell cell(double x, double y) const {
    return grid_cell(x0, dx, nx, y0, dy, ny, periodic_x ? wrap_into(x, x0, period_x()) : x,
                     periodic_y ? wrap_into(y, y0, period_y()) : y);
  }
  double node(std::size_t i, std::size_t j) const { return z[i + nx * j]; }

  // h(x, y), bilinear in the four nodes around (x, y); or in those of cell c (found once for
  // maps on the same grid, as the spread's floor and its bounds).
  double at(double x, double y) const { return at(cell(x, y)); }
  double at(const GridCell& c) const {
    return (1 - c.fy) * ((1 - c.fx) * node(c.i, c.j) + c.fx * node(c.i + 1, c.j)) +
           c.fy * ((1 - c.fx) * node(c.i, c.j + 1) + c.fx * node(c.i + 1, c.j + 1));
  }
  // (dh/dx, dh/dy) of the bilinear patch at (x, y) (zero across a clamped edge).
  std::array<double, 2> slope(double x, double y) const {
    const GridCell c = cell(x, y);
    const double ux = (x - x0) / dx, uy = (y - y0) / dy;
    const bool inside_x = periodic_x || (ux > 0 && ux < static_cast<double>(nx - 1));
    const bool inside_y = periodic_y || (uy > 0 && uy < static_cast<double>(ny - 1));
    const double sx = ((1 - c.fy) * (node(c.i + 1, c.j) - node(c.i, c.j)) +
                       c.fy * (node(c.i + 1, c.j + 1) - node(c.i, c.j + 1))) / dx;
    const double sy = ((1 - c.fx) * (node(c.i, c.j + 1) - node(c.i, c.j)) +
                       c.fx * (node(c.i + 1, c.j + 1) - node(c.i + 1, c.j))) / dy;
    return {inside_x ? sx : 0.0, inside_y ? sy : 0.0};
  }
  // A surface periodic along x or y has one edge line, not two: the nodes of the two edge rows
  // (columns) along a periodic axis take their mean, which keeps their sum, so the volume under
  // the surface (each node owning dx dy) is unchanged. A sphere crossing the seam then finds the
  // surface it left, instead of a step it would be deep inside.
  void join_periodic_edges() {
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

  // The surface a sphere touches (the spread's floor, fusion's capture): each cell cut into two
  // triangles along its diagonal from node (i, j) to (i + 1, j + 1), held beyond the grid as at().
  // Triangles make the nearest point exact (closest_point_triangle.hpp), so a contact along the
  // line to it is the gradient of a potential (surface_contacts.hpp, which also measures a
  // sphere's overlap with it). Within a cell they depart
  // from the bilinear at() by at most |z(i, j) + z(i + 1, j + 1) - z(i + 1, j) - z(i, j + 1)| / 4,
  // at its centre. Triangle t of cell (i, j) is 2 (i + (nx - 1) j) + (0: corners (i, j),
  // (i + 1, j), (i + 1, j + 1); 1: (i, j), (i + 1, j + 1), (i, j + 1)).
  double surface(double x, double y) const { return surface(cell(x, y)); }
  double surface(const GridCell& c) const {
    const double a = node(c.i, c.j), diagonal = node(c.i + 1, c.j + 1);
    if (c.fx >= c.fy) return a + c.fx * (node(c.i + 1, c.j) - a) + c.fy * (diagonal - node(c.i + 1, c.j));
    return a + c.fy * (node(c.i, c.j + 1) - a) + c.fx * (diagonal - node(c.i, c.j + 1));
  }
  std::size_t triangle_at(double x, double y) const { return triangle_at(cell(x, y)); }
  std::size_t triangle_at(const GridCell& c) const {
    return 2 * (c.i + (nx - 1) * c.j) + (c.fx >= c.fy ? 0 : 1);
  }
  // Triangle t's corners, moved by `shift` (an image across a periodic seam).
  std::array<Point3, 3> triangle(std::size_t t, std::array<double, 2> shift = {0, 0}) const {
    const std::size_t i = (t / 2) % (nx - 1), j = (t / 2) / (nx - 1);
    const double xa = x0 + dx * static_cast<double>(i) + shift[0];
    const double ya = y0 + dy * static_cast<double>(j) + shift[1];
    const Point3 a{xa, ya, node(i, j)}, c{xa + dx, ya + dy, node(i + 1, j + 1)};
    if (t % 2 == 0) return {a, Point3{xa + dx, ya, node(i + 1, j)}, c};
    return {a, c, Point3{xa, ya + dy, node(i, j + 1)}};
  }
  // The shift of an image moved by whole cells along x and y (periods' worth on a periodic axis).
  std::array<double, 2> image_shift(std::array<std::ptrdiff_t, 2> cells) const {
    return {dx * static_cast<double>(cells[0]), dy * static_cast<double>(cells[1])};
  }
  // (x, y) clamped onto the grid along a bounded axis (where the surface held beyond it is
  // measured from); along a periodic one as given (the triangles near it come as images).
  std::array<double, 2> clamp(double x, double y) const {
    return {periodic_x ? x : std::clamp(x, x0, x0 + period_x()),
            periodic_y ? y : std::clamp(y, y0, y0 + period_y())};
  }
  // f(t, shift) for each triangle t that may hold a point within `reach` of (x, y, zc), moved by
  // `shift` to the image nearest (x, y) on a periodic axis: those of the cells whose box (the
  // cell up to its highest node) comes within `reach`. A sphere resting on the surface has most
  // of its footprint's cells just under its lowest point, and the box's horizontal distance
  // rules them out: only the cells near where it touches remain. A reach of half a period or
  // more would meet a cell twice.
  template <class F>
  void for_each_triangle_near(double x, double y, double zc, double reach, F&& f) const {
    const auto [i0, i1] = cell_span(x0, dx, nx, periodic_x, x - reach, x + reach);
    const auto [j0, j1] = cell_span(y0, dy, ny, periodic_y, y - reach, y + reach);
    for (std::ptrdiff_t jj = j0; jj <= j1; ++jj) {
      const std::size_t j = wrap_index(jj, ny);
      const double ya = y0 + dy * static_cast<double>(jj);
      const double beside_y = std::max({0.0, ya - y, y - ya - dy});
      for (std::ptrdiff_t ii = i0; ii <= i1; ++ii) {
        const std::size_t i = wrap_index(ii, nx);
        const double xa = x0 + dx * static_cast<double>(ii);
        const double beside_x = std::max({0.0, xa - x, x - xa - dx});
        const double top = std::max({node(i, j), node(i + 1, j), node(i, j + 1), node(i + 1, j + 1)});
        const double above = std::max(0.0, zc - top);
        if (beside_x * beside_x + beside_y * beside_y + above * above >= reach * reach) continue;
        const std::array<double, 2> shift =
            image_shift({ii - static_cast<std::ptrdiff_t>(i), jj - static_cast<std::ptrdiff_t>(j)});
        f(2 * (i + (nx - 1) * j), shift);
        f(2 * (i + (nx - 1) * j) + 1, shift);
      }
    }
  }

  // Node or cell index k along a periodic axis of n nodes (n - 1 of them distinct: the last is
  // the first), wrapped into 0 .. n - 2; k itself when it lies there already.
  static std::size_t wrap_index(std::ptrdiff_t k, std::size_t n) {
    const auto distinct = static_cast<std::ptrdiff_t>(n) - 1;
    return static_cast<std::size_t>(((k % distinct) + distinct) % distinct);
  }

 private:
  // The cells meeting [a, b] along one axis (lower node from lo in steps d, n nodes): clamped
  // onto the grid along a bounded axis, as unwrapped indices along a periodic one.
  static std::array<std::ptrdiff_t, 2> cell_span(double lo, double d, std::size_t n, bool periodic,
                                                 double a, double b) {
    const auto index = [&](double v) { return static_cast<std::ptrdiff_t>(std::floor((v - lo) / d)); };
    if (periodic) return {index(a), index(b)};
    const auto last = static_cast<std::ptrdiff_t>(n) - 2;
    return {std::clamp<std::ptrdiff_t>(index(a), 0, last), std::clamp<std::ptrdiff_t>(index(b), 0, last)};
  }
};

}  // namespace powderbed::bed
