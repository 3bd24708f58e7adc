// surface_contacts.hpp: the local minima of the distance from a sphere's centre to a HeightMap's
// triangles.
#include "powderbed/bed/surface_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

namespace powderbed::bed {

namespace {

// A feature of the triangulated grid, named once whichever triangle finds it: a node, an edge
// (its lower node and its direction: 0 along x, 1 along y, 2 the cell's diagonal) or a face.
enum FeatureKind : std::uint64_t { kNode, kEdge, kFace };
constexpr std::uint64_t feature_key(FeatureKind kind, std::uint64_t value) { return 3 * value + kind; }

// Across a periodic seam the last node row is the first: a feature there is named by its node
// in the first.
std::uint64_t feature_of(const HeightMap& m, std::size_t t, TriangleFeature f) {
  const std::size_t i = (t / 2) % (m.nx - 1), j = (t / 2) / (m.nx - 1);
  const auto index = [&](std::size_t a, std::size_t b) {
    return (m.periodic_x && a == m.nx - 1 ? 0 : a) + m.nx * (m.periodic_y && b == m.ny - 1 ? 0 : b);
  };
  const auto node = [&](std::size_t a, std::size_t b) { return feature_key(kNode, index(a, b)); };
  const auto edge = [&](std::size_t a, std::size_t b, int direction) {
    return feature_key(kEdge, 3 * index(a, b) + static_cast<std::uint64_t>(direction));
  };
  using F = TriangleFeature;
  const bool lower = t % 2 == 0;  // corners (i, j), (i + 1, j), (i + 1, j + 1); else (i, j), (i + 1, j + 1), (i, j + 1)
  switch (f) {
    case F::vertex_a: return node(i, j);
    case F::vertex_b: return lower ? node(i + 1, j) : node(i + 1, j + 1);
    case F::vertex_c: return lower ? node(i + 1, j + 1) : node(i, j + 1);
    case F::edge_ab: return lower ? edge(i, j, 0) : edge(i, j, 2);
    case F::edge_ac: return lower ? edge(i, j, 2) : edge(i, j, 1);
    case F::edge_bc: return lower ? edge(i + 1, j, 1) : edge(i, j + 1, 0);
    case F::face: break;
  }
  return feature_key(kFace, t);
}

// How many triangles of the grid hold a node or an edge (on a periodic axis, every node is
// inner).
std::size_t triangles_holding(const HeightMap& m, std::uint64_t key) {
  const std::uint64_t value = key / 3;
  const auto inner = [](std::size_t k, std::size_t n, bool periodic) {
    return periodic ? 2 : std::size_t{k > 0} + std::size_t{k + 1 < n};
  };
  if (key % 3 == kNode) {
    const std::size_t i = value % m.nx, j = value / m.nx;
    const bool left = m.periodic_x || i > 0, right = m.periodic_x || i + 1 < m.nx;
    const bool below = m.periodic_y || j > 0, above = m.periodic_y || j + 1 < m.ny;
    return 2 * (right && above) + (left && above) + 2 * (left && below) + (right && below);
  }
  const std::size_t n = value / 3, i = n % m.nx, j = n / m.nx;
  switch (value % 3) {
    case 0: return inner(j, m.ny, m.periodic_y);  // along x: the cells above and below
    case 1: return inner(i, m.nx, m.periodic_x);  // along y: the cells left and right
    default: return 2;                            // a cell's diagonal
  }
}

struct Candidate {
  std::uint64_t feature;
  std::size_t facet;
  Point3 point;
  double distance;
};

// The contacts among the triangles `each` visits (f(t, shift) for each): the candidates within
// r, a node or edge kept only where every triangle holding it found it, deepest first.
template <class Each>
std::size_t contacts_among(const HeightMap& m, double x, double y, double zc, double r, Each&& each,
                           std::array<SurfaceContact, kMaxSurfaceContacts>& out) {
  thread_local std::vector<Candidate> found;  // reused: the spread asks every step
  found.clear();
  const auto [xc, yc] = m.clamp(x, y);
  const Point3 centre{xc, yc, zc};
  each([&](std::size_t t, std::array<double, 2> shift) {
    const auto [a, b, c] = m.triangle(t, shift);
    const TrianglePoint q = closest_point_on_triangle(centre, a, b, c);
    const double ex = q.point[0] - xc, ey = q.point[1] - yc, ez = q.point[2] - zc;
    const double distance = std::sqrt(ex * ex + ey * ey + ez * ez);
    if (distance < r) found.push_back({feature_of(m, t, q.feature), t, q.point, distance});
  });
  std::sort(found.begin(), found.end(), [](const Candidate& p, const Candidate& q) {
    return std::tie(p.feature, p.facet) < std::tie(q.feature, q.facet);
  });
  std::vector<Candidate>::iterator kept = found.begin();
  for (auto group = found.begin(); group != found.end();) {
    auto end = group;
    while (end != found.end() && end->feature == group->feature) ++end;
    const bool face = group->feature % 3 == kFace;
    if (face || static_cast<std::size_t>(end - group) == triangles_holding(m, group->feature)) *kept++ = *group;
    group = end;
  }
  std::sort(found.begin(), kept, [](const Candidate& p, const Candidate& q) {
    return std::tie(p.distance, p.facet) < std::tie(q.distance, q.facet);
  });
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(kept - found.begin()), kMaxSurfaceContacts);
  for (std::size_t k = 0; k < count; ++k) {
    const Candidate& c = found[k];
    out[k] = {c.facet, {c.point[0] - xc, c.point[1] - yc, c.point[2] - zc}, c.distance};
  }
  return count;
}

}  // namespace

std::size_t surface_contacts(const HeightMap& m, double x, double y, double zc, double r,
                             std::array<SurfaceContact, kMaxSurfaceContacts>& out) {
  const auto [xc, yc] = m.clamp(x, y);
  return contacts_among(m, x, y, zc, r, [&](auto&& f) { m.for_each_triangle_near(xc, yc, zc, r, f); }, out);
}

void triangles_near(const HeightMap& m, double x, double y, double zc, double reach,
                    std::vector<TriangleImage>& near) {
  const auto [xc, yc] = m.clamp(x, y);
  const Point3 centre{xc, yc, zc};
  m.for_each_triangle_near(xc, yc, zc, reach, [&](std::size_t t, std::array<double, 2> shift) {
    const auto [a, b, c] = m.triangle(t, shift);
    const TrianglePoint q = closest_point_on_triangle(centre, a, b, c);
    const double ex = q.point[0] - xc, ey = q.point[1] - yc, ez = q.point[2] - zc;
    if (ex * ex + ey * ey + ez * ez >= reach * reach) return;
    near.push_back({t, {std::lround(shift[0] / m.dx), std::lround(shift[1] / m.dy)}});
  });
}

std::size_t surface_contacts(const HeightMap& m, double x, double y, double zc, double r,
                             std::span<const TriangleImage> near, std::array<std::ptrdiff_t, 2> wrapped,
                             std::array<SurfaceContact, kMaxSurfaceContacts>& out) {
  return contacts_among(m, x, y, zc, r, [&](auto&& f) {
    for (const TriangleImage& n : near)
      f(n.triangle, m.image_shift({n.cells[0] + wrapped[0], n.cells[1] + wrapped[1]}));
  }, out);
}

double surface_overlap(const HeightMap& m, double x, double y, double zc, double r) {
  const auto [xc, yc] = m.clamp(x, y);
  const double foot = m.surface(xc, yc) - zc;
  if (foot >= 0) return r + foot;
  std::array<SurfaceContact, kMaxSurfaceContacts> c;
  return surface_contacts(m, x, y, zc, r, c) > 0 ? r - c[0].distance : 0.0;
}

}  // namespace powderbed::bed
