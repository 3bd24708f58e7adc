#pragma once
// Closed-form positions of a new particle touching two or three partners (docs/physics.md §3,
// 2-contact and 3-contact). A partner is a placed particle (|x - c| = R + r) or a wall plane
// (n . x = offset + r: the new centre sits r inside the wall). The first partner is always a
// particle. Subtracting its sphere equation from the others leaves linear equations, so
//   2D, two partners: a line cut by a circle   -> 0 or 2 points (circle–circle intersection)
//   3D, two partners: a plane cut by a sphere  -> a circle of solutions
//   3D, three partners: a line cut by a sphere -> 0 or 2 mirror points (trilateration)
// Near-tangent cases (discriminant ~ 0) are clamped when the discriminant is above
// -kClampTolerance R^2 (the clamped point has a gap of at most ~kClampTolerance / 2 relative
// to both partners, never an overlap); colinear centres (parallel linear equations) and any
// non-finite result give no solution, never NaN.
#include <algorithm>
#include <array>
#include <cmath>

namespace powderbed::packgen {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }

struct Partner {
  bool is_plane = false;
  Vec3 centre;        // particle centre
  double radius = 0;  // particle radius
  Vec3 normal;        // plane: unit normal pointing into the domain
  double offset = 0;  // plane: n . x = offset on the wall

  static Partner particle(Vec3 c, double r) { return {false, c, r, {}, 0}; }
  static Partner plane(Vec3 n, double offset) { return {true, {}, 0, n, offset}; }
};

constexpr double kClampTolerance = 1e-12;

// Whether a new particle of radius r can touch both partners at once (docs/physics.md §3
// 2-contact reach; partners relative to any common origin): particles within r_a + r_b + 2r,
// a particle within r_a + 2r of a wall, walls on different axes (axis-aligned normals: dot 0).
// The one reach test of both placement algorithms (the 3-contact partner pairs of the contact
// approaches and of lowest-site growth); forced inline as it runs for every partner pair
// (packgen/src/placement_core.hpp says why).
[[gnu::always_inline]] inline bool in_reach(const Partner& a, const Partner& b, double r) {
  if (a.is_plane && b.is_plane) return dot(a.normal, b.normal) == 0;
  if (a.is_plane || b.is_plane) {
    const Partner& w = a.is_plane ? a : b;
    const Partner& q = a.is_plane ? b : a;
    return dot(w.normal, q.centre) - w.offset <= q.radius + 2 * r;
  }
  const Vec3 d = b.centre - a.centre;
  const double s = a.radius + b.radius + 2 * r;
  return dot(d, d) <= s * s;
}

// Distance error of x as a contact of `partner` for a new particle of radius r, relative to
// the contact distance (R + r for particles, r for planes).
double contact_residual(const Partner& partner, Vec3 x, double r);

// 2D (z = 0): up to two centres touching particle a and partner b. Returns the count (0, 1 or 2).
int touch_two_2d(const Partner& a, const Partner& b, double r, std::array<Vec3, 2>& out);

// 3D: the circle of centres touching particle a and partner b.
struct Circle {
  Vec3 centre, e1, e2;  // e1, e2: orthonormal, spanning the circle's plane
  double radius = 0;
  Vec3 at(double angle) const {
    return centre + (radius * std::cos(angle)) * e1 + (radius * std::sin(angle)) * e2;
  }
};
bool touch_two_3d(const Partner& a, const Partner& b, double r, Circle& out);

// 3D: up to two mirror centres touching particle a and partners b and c. Returns 0, 1 or 2.
int touch_three_3d(const Partner& a, const Partner& b, const Partner& c, double r,
                   std::array<Vec3, 2>& out);

// The plane n . y = e (y = x - c_a) on which partner b's contact equation cuts the sphere
// |y| = R_a + r of particle a (for a particle b: the plane of the circle of centres touching a
// and b). It depends on the pair and r only, so a loop over the triples (a, b, c) of one new
// particle a computes it once per partner and reuses it (docs/physics.md §3 3-contact).
struct PairPlane {
  Vec3 n;
  double e = 0;
  double nn = 0;  // |n|^2
};
PairPlane pair_plane(const Partner& a, const Partner& b, double r);
// Trilateration from two pair planes of the same particle a (rho = R_a + r): 0, or 2 points
// relative to c_a, y[0] on the +u side and y[1] on the -u side of u = p1.n x p2.n. Inline: it
// is the innermost step of the lowest-site search. The line is y = y0 + s u with
// y0 = w / |u|^2, w = e1 (n2 x u) + e2 (u x n1) = (e1 n2 - e2 n1) x u (y0 . u = 0); it meets
// the sphere where s^2 |u|^2 = rho^2 - |y0|^2, i.e. D = rho^2 |u|^4 - |w|^2 >= 0, tested
// before any division; near-tangent D (above -kClampTolerance rho^2 |u|^4) is clamped to 0,
// NaN gives no solution.
inline int trilaterate(const PairPlane& p1, const PairPlane& p2, double rho,
                       std::array<Vec3, 2>& y) {
  const Vec3 u = cross(p1.n, p2.n);
  const double u2 = dot(u, u);
  // Colinear centres (or parallel walls): the two equations are (nearly) parallel.
  if (!(u2 > 1e-24 * p1.nn * p2.nn)) return 0;
  const Vec3 w = cross(p1.e * p2.n - p2.e * p1.n, u);
  const double sphere = rho * rho * u2 * u2;
  const double d = sphere - dot(w, w);
  if (!(d >= -kClampTolerance * sphere)) return 0;
  const double inv = 1.0 / u2;
  const Vec3 y0 = inv * w;
  const double s = std::sqrt(std::max(d, 0.0) * inv) * inv;  // = sqrt(rho^2 - |y0|^2) / |u|
  if (!std::isfinite(s)) return 0;
  y[0] = y0 + s * u;
  y[1] = y0 - s * u;
  return 2;
}

// The trilateration of touch_three_3d without its final check: 0, or 2 with out[0] on the +u
// side and out[1] on the -u side (u = n_ab x n_ac, site_heap.hpp). Hot loops filter the points
// by cheaper tests first and then confirm the survivors with touches_all.
int trilaterate(const Partner& a, const Partner& b, const Partner& c, double r,
                std::array<Vec3, 2>& out);
// True when x is a contact of every partner to within the verification tolerance (1e-9).
bool touches_all(const Partner* partners, int count, Vec3 x, double r);

}  // namespace powderbed::packgen
