#pragma once
// The point of a triangle nearest a point p: the projection of p onto the triangle's plane
// when it falls inside, else the nearest point of the edge or the vertex whose Voronoi region
// holds p. The regions are told apart by the signs of dot products (barycentric coordinates),
// as in Ericson, Real-Time Collision Detection (2005) §5.1.5. It is exact, so the distance to a
// surface of triangles is a continuous function of p whose gradient is the unit vector from
// the nearest point to p: a contact force along that vector is the gradient of a potential
// (bed/height_map.hpp HeightMap::contacts).
#include <array>

namespace powderbed::bed {

using Point3 = std::array<double, 3>;

// Which feature of triangle (a, b, c) holds the nearest point.
enum class TriangleFeature { vertex_a, vertex_b, vertex_c, edge_ab, edge_ac, edge_bc, face };

struct TrianglePoint {
  Point3 point;
  TriangleFeature feature;
};

inline TrianglePoint closest_point_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
  using F = TriangleFeature;
  const auto sub = [](const Point3& u, const Point3& v) { return Point3{u[0] - v[0], u[1] - v[1], u[2] - v[2]}; };
  const auto dot = [](const Point3& u, const Point3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const auto along = [](const Point3& o, const Point3& e, double t) {
    return Point3{o[0] + t * e[0], o[1] + t * e[1], o[2] + t * e[2]};
  };
  const Point3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {a, F::vertex_a};
  const Point3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {b, F::vertex_b};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {along(a, ab, d1 / (d1 - d3)), F::edge_ab};
  const Point3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {c, F::vertex_c};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {along(a, ac, d2 / (d2 - d6)), F::edge_ac};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return {along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))), F::edge_bc};
  const double denominator = 1.0 / (va + vb + vc);
  const double v = vb * denominator, w = vc * denominator;
  return {{a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w}, F::face};
}

}  // namespace powderbed::bed
