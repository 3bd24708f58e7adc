// Local packing fractions from the radical (Laguerre) tessellation, docs/physics.md §2: CGAL regular
// triangulation of the centres weighted by r^2. The Laguerre cell of a vertex v is cut, cell of
// the triangulation by cell, into signed orthoschemes, one per flag v ⊂ edge vw ⊂ facet vwu ⊂
// cell vwut: with p the cell's weighted circumcentre (power-equidistant from its four vertices),
// p's foot on the line vw is where the radical plane of v and w crosses it, and p's foot on the
// plane vwu is the facet's power centre, so the tetrahedron (v, foot on vw, foot on vwu, p) has
// three mutually perpendicular legs and volume x y z / 6, where x, y, z are the coordinates of
// p - v along the frame Gram–Schmidt makes of (w - v, u - v, t - v). A coordinate is negative
// when p lies beyond that edge, facet or cell, and the signed sum over every flag of v is the
// cell's volume (the barycentric subdivision of the cell's faces, each face a fan of such
// triangles around its foot on its edge). One pass over the cells, each visited once; the edge
// pass this replaces circulated around every edge (six visits per cell, 38 % of bedstat
// --voronoi on 1e6 spheres).
// A cell counts as cut by the boundary (NaN) when its vertex is on the convex hull (an infinite
// incident cell) or one of its corners (a weighted circumcentre) lies outside the domain box.
// Periodic axes are treated as walls here: cells crossing a periodic face get NaN too.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Regular_triangulation_cell_base_3.h>
#include <CGAL/Regular_triangulation_vertex_base_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <utility>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/bed/stats.hpp"

namespace powderbed::bed {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<
    std::size_t, Kernel, CGAL::Regular_triangulation_vertex_base_3<Kernel>>;
using CellBase =
    CGAL::Regular_triangulation_cell_base_3<Kernel, CGAL::Triangulation_cell_base_3<Kernel>,
                                            CGAL::Discard_hidden_points>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Regular = CGAL::Regular_triangulation_3<Kernel, Tds>;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;

void check_positions(const Bed& bed) {
  const std::vector<double>* arrays[4] = {&bed.x, &bed.y, &bed.z, &bed.radius};
  const char* names[4] = {"position x", "position y", "position z", "radius"};
  for (int a = 0; a < 4; ++a) {
    if (arrays[a]->size() != bed.n()) {
      throw InputError(fmt::format(
          "voronoi_stats: {} has {} entries for {} particles (accepted: one per particle)",
          names[a], arrays[a]->size(), bed.n()));
    }
    for (std::size_t i = 0; i < bed.n(); ++i) {
      if (!std::isfinite((*arrays[a])[i])) {
        throw InputError(fmt::format("voronoi_stats: {}[{}] is {:g} (accepted: finite numbers)",
                                     names[a], i, (*arrays[a])[i]));
      }
    }
  }
}

// The unit vector along a.
Vector unit(const Vector& a) { return a / std::sqrt(a.squared_length()); }

// The signed orthoschemes of one finite cell, added to its four vertices' volumes (the file's
// first comment). The frame of flag (v, w, u, t) is e along w - v, g along the part of u - v
// normal to e, n along the part of t - v normal to both; e flips with the edge's direction, g
// depends only on the edge and u, n only on the facet and t, so each is computed once per cell.
void add_cell_volumes(Regular::Cell_handle c, const Point& p, std::vector<double>& volume) {
  Point v[4];
  for (int k = 0; k < 4; ++k) v[k] = c->vertex(k)->point().point();
  // n[t]: unit normal of the facet opposite vertex t, towards t; z[t]: p's height above it.
  Vector n[4];
  double z[4];
  for (int t = 0; t < 4; ++t) {
    const int a = (t + 1) % 4, b = (t + 2) % 4, d = (t + 3) % 4;
    n[t] = unit(CGAL::cross_product(v[b] - v[a], v[d] - v[a]));
    if ((v[t] - v[a]) * n[t] < 0) n[t] = -n[t];
    z[t] = (p - v[a]) * n[t];
  }
  double add[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      const Vector e = unit(v[j] - v[i]);
      const double xi = (p - v[i]) * e, xj = (v[j] - p) * e;  // along i -> j, and j -> i
      for (int u = 0; u < 4; ++u) {
        if (u == i || u == j) continue;
        const int t = 6 - i - j - u;  // the fourth vertex
        Vector g = v[u] - v[i];
        g = unit(g - (g * e) * e);
        const double y = (p - v[i]) * g;
        add[i] += xi * y * z[t];
        add[j] += xj * y * z[t];
      }
    }
  }
  for (int k = 0; k < 4; ++k) volume[c->vertex(k)->info()] += add[k] / 6.0;
}

// The Laguerre cell volumes (every finite cell's orthoschemes) and which vertices are cut: a
// vertex is cut when an incident cell is infinite or has its weighted circumcentre outside the
// box. One pass over the cells; a cut vertex's sum is incomplete and never read.
struct Cells {
  std::vector<double> volume;
  std::vector<char> cut;
};

Cells laguerre_cells(const Regular& rt, const Domain& d, std::size_t n) {
  Cells out{std::vector<double>(n, 0.0), std::vector<char>(n, 0)};
  const auto inside = [&](const Point& p) {
    for (int a = 0; a < 3; ++a) {
      if (!(p[a] >= d.lower[a] && p[a] <= d.upper[a])) return false;
    }
    return true;
  };
  for (auto c = rt.all_cells_begin(); c != rt.all_cells_end(); ++c) {
    bool cut = rt.is_infinite(c);
    if (!cut) {
      const Point p = rt.dual(c);
      add_cell_volumes(c, p, out.volume);
      cut = !inside(p);
    }
    if (!cut) continue;
    for (int k = 0; k < 4; ++k) {
      if (!rt.is_infinite(c->vertex(k))) out.cut[c->vertex(k)->info()] = 1;
    }
  }
  return out;
}

// Each uncut particle's volume over its cell's, and their mean and sample standard deviation.
void local_fractions(const Regular& rt, const Bed& bed, const Cells& cells, VoronoiStats& out) {
  double sum = 0;
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) {
    const std::size_t i = v->info();
    if (cells.cut[i]) continue;
    const double r = bed.radius[i];
    out.local_fraction[i] = sphere_volume(r) / cells.volume[i];
    ++out.interior;
    sum += out.local_fraction[i];
  }
  if (out.interior == 0) return;
  const auto m = static_cast<double>(out.interior);
  out.mean = sum / m;
  double squares = 0;
  for (const double phi : out.local_fraction) {
    if (!std::isnan(phi)) squares += (phi - out.mean) * (phi - out.mean);
  }
  // Sample standard deviation (m - 1); 0 for a single interior cell.
  out.sd = out.interior > 1 ? std::sqrt(squares / (m - 1)) : 0.0;
}

}  // namespace

VoronoiStats voronoi_stats(const Bed& bed) {
  const Domain& d = bed.domain;
  d.validate("voronoi_stats");
  if (d.dimension != 3) {
    throw InputError(
        fmt::format("voronoi_stats: bed dimension is {} (accepted: 3)", d.dimension));
  }
  check_positions(bed);
  const std::size_t n = bed.n();
  VoronoiStats out;
  out.local_fraction.assign(n, std::numeric_limits<double>::quiet_NaN());

  std::vector<std::pair<Regular::Weighted_point, std::size_t>> points;
  points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = bed.radius[i];
    points.emplace_back(Regular::Weighted_point(Point(bed.x[i], bed.y[i], bed.z[i]), r * r), i);
  }
  Regular rt;
  rt.insert(points.begin(), points.end());
  if (rt.dimension() < 3) return out;
  local_fractions(rt, bed, laguerre_cells(rt, d, n), out);
  return out;
}

}  // namespace powderbed::bed
