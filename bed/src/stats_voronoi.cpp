// Local packing fractions from the radical (Laguerre) tessellation, docs/physics.md §2: CGAL regular
// triangulation of the centres weighted by r^2. The Laguerre cell of a vertex v is bounded by one
// face per triangulation edge (v, w), the polygon of the weighted circumcentres of the cells
// around that edge, lying in the radical plane with outward normal n = (w - v)/|w - v|. By the
// divergence theorem the cell volume is sum over faces of (1/3) area * ((p - v) . n), p any point
// of the face; one pass over the edges accumulates every cell.
// A cell counts as cut by the boundary (NaN) when its vertex is on the convex hull (an infinite
// incident cell) or one of its corners (a weighted circumcentre) lies outside the domain box.
// Periodic axes are treated as walls here: cells crossing a periodic face get NaN too.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Regular_triangulation_cell_base_3.h>
#include <CGAL/Regular_triangulation_vertex_base_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/stats.hpp"

namespace powderbed::bed {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<
    std::size_t, Kernel, CGAL::Regular_triangulation_vertex_base_3<Kernel>>;
using CellBase = CGAL::Triangulation_cell_base_with_info_3<
    std::size_t, Kernel,
    CGAL::Regular_triangulation_cell_base_3<Kernel, CGAL::Triangulation_cell_base_3<Kernel>,
                                            CGAL::Discard_hidden_points>>;
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

// The triangulation's corners: the weighted circumcentre of every finite cell (its index in
// `corner` stored as the cell's info), and which vertices are cut: a vertex is cut when any
// incident cell is infinite or has its circumcentre outside the box.
struct Corners {
  std::vector<Point> corner;
  std::vector<char> cut;
};

Corners cell_corners(Regular& rt, const Domain& d, std::size_t n) {
  Corners out;
  out.cut.assign(n, 0);
  out.corner.reserve(rt.number_of_finite_cells());
  auto inside = [&](const Point& p) {
    for (int a = 0; a < 3; ++a) {
      if (!(p[a] >= d.lower[a] && p[a] <= d.upper[a])) return false;
    }
    return true;
  };
  for (auto c = rt.all_cells_begin(); c != rt.all_cells_end(); ++c) {
    bool bad = rt.is_infinite(c);
    if (!bad) {
      c->info() = out.corner.size();
      out.corner.push_back(rt.dual(c));
      bad = !inside(out.corner.back());
    }
    if (!bad) continue;
    for (int k = 0; k < 4; ++k) {
      if (!rt.is_infinite(c->vertex(k))) out.cut[c->vertex(k)->info()] = 1;
    }
  }
  return out;
}

// Area of a planar polygon (its corners in order): half the norm of the summed fan cross
// products.
double polygon_area(const std::vector<Point>& face) {
  Vector area(0, 0, 0);
  for (std::size_t k = 1; k + 1 < face.size(); ++k) {
    area = area + CGAL::cross_product(face[k] - face[0], face[k + 1] - face[0]);
  }
  return 0.5 * std::sqrt(area.squared_length());
}

// The Laguerre cell volumes of the uncut vertices in one pass over the edges (the file's first
// comment): the face of edge (v, w) adds (1/3) area ((p - v) . n) to v's cell and
// (1/3) area ((p - w) . (-n)) to w's, n the unit vector from v to w.
std::vector<double> cell_volumes(const Regular& rt, const Corners& corners, std::size_t n) {
  std::vector<double> volume(n, 0.0);
  std::vector<Point> face;
  for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e) {
    const auto v = e->first->vertex(e->second), w = e->first->vertex(e->third);
    const std::size_t iv = v->info(), iw = w->info();
    if (corners.cut[iv] && corners.cut[iw]) continue;
    // One end is uncut, so every cell around the edge is finite.
    face.clear();
    auto cell = rt.incident_cells(*e);
    const auto done = cell;
    do {
      face.push_back(corners.corner[cell->info()]);
    } while (++cell != done);
    const double face_area = polygon_area(face);
    const Point& pv = v->point().point();
    const Point& pw = w->point().point();
    Vector normal = pw - pv;
    normal = normal / std::sqrt(normal.squared_length());
    volume[iv] += face_area * ((face[0] - pv) * normal) / 3.0;
    volume[iw] -= face_area * ((face[0] - pw) * normal) / 3.0;
  }
  return volume;
}

// Each uncut particle's volume over its cell's, and their mean and sample standard deviation.
void local_fractions(const Regular& rt, const Bed& bed, const Corners& corners,
                     const std::vector<double>& volume, VoronoiStats& out) {
  double sum = 0;
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) {
    const std::size_t i = v->info();
    if (corners.cut[i]) continue;
    const double r = bed.radius[i];
    out.local_fraction[i] = 4.0 / 3.0 * std::numbers::pi * r * r * r / volume[i];
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
  const Corners corners = cell_corners(rt, d, n);
  local_fractions(rt, bed, corners, cell_volumes(rt, corners, n), out);
  return out;
}

}  // namespace powderbed::bed
