#include "powderbed/packgen/contact_geometry.hpp"

#include <algorithm>

namespace powderbed::packgen {

namespace {

// Solutions are verified against every contact: a result further than this from touching is
// an ill-conditioned (near-colinear) case and is dropped; good cases sit near 1e-15.
constexpr double kVerifyTolerance = 1e-9;

// Linear equation n . y = e (y = x - c_a) that partner b adds to sphere a (|y| = rho_a).
struct Linear {
  Vec3 n;
  double e = 0;
};

Linear linearise(const Partner& a, const Partner& b, double r) {
  if (b.is_plane) return {b.normal, b.offset + r - dot(b.normal, a.centre)};
  // |y|^2 = rho_a^2 and |y - d|^2 = rho_b^2  =>  2 d . y = rho_a^2 - rho_b^2 + |d|^2, written
  // as a product so that equal radii cancel exactly.
  const Vec3 d = b.centre - a.centre;
  const double rho_a = a.radius + r, rho_b = b.radius + r;
  return {2.0 * d, (rho_a - rho_b) * (rho_a + rho_b) + dot(d, d)};
}

// t^2 = rho^2 - |y0|^2, clamped near zero; false when there is no real solution.
bool half_chord(double rho, Vec3 y0, double& t) {
  const double disc = rho * rho - dot(y0, y0);
  if (!(disc >= -kClampTolerance * rho * rho)) return false;  // also rejects NaN
  t = std::sqrt(std::max(disc, 0.0));
  return std::isfinite(t);
}

bool verified(const Partner* partners, int count, Vec3 x, double r) {
  for (int k = 0; k < count; ++k) {
    if (!(contact_residual(partners[k], x, r) <= kVerifyTolerance)) return false;
  }
  return true;
}

// Moves the verified ones of the two candidates in `out` to the front; returns how many.
int keep_verified(const Partner* partners, int count, double r, std::array<Vec3, 2>& out) {
  int kept = 0;
  for (int s = 0; s < 2; ++s) {
    if (verified(partners, count, out[s], r)) out[kept++] = out[s];
  }
  return kept;
}

}  // namespace

double contact_residual(const Partner& p, Vec3 x, double r) {
  if (p.is_plane) return std::abs(dot(p.normal, x) - p.offset - r) / r;
  return std::abs(norm(x - p.centre) - (p.radius + r)) / (p.radius + r);
}

int touch_two_2d(const Partner& a, const Partner& b, double r, std::array<Vec3, 2>& out) {
  const Linear l = linearise(a, b, r);
  const double n2 = l.n.x * l.n.x + l.n.y * l.n.y;
  if (!(n2 > 0)) return 0;  // coincident centres: no line
  const Vec3 y0 = (l.e / n2) * Vec3{l.n.x, l.n.y, 0};
  double t = 0;
  if (!half_chord(a.radius + r, y0, t)) return 0;
  const double inv = 1.0 / std::sqrt(n2);
  const Vec3 u{-l.n.y * inv, l.n.x * inv, 0};
  out[0] = a.centre + y0 + t * u;
  out[1] = a.centre + y0 - t * u;
  const Partner partners[2] = {a, b};
  return keep_verified(partners, 2, r, out);
}

bool touch_two_3d(const Partner& a, const Partner& b, double r, Circle& out) {
  const Linear l = linearise(a, b, r);
  const double n2 = dot(l.n, l.n);
  if (!(n2 > 0)) return false;
  const Vec3 y0 = (l.e / n2) * l.n;
  double t = 0;
  if (!half_chord(a.radius + r, y0, t)) return false;
  const Vec3 n = (1.0 / std::sqrt(n2)) * l.n;
  // e1: the axis least aligned with n, made orthogonal to it.
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  const Vec3 axis = (ax <= ay && ax <= az) ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
  Vec3 e1 = cross(n, axis);
  e1 = (1.0 / norm(e1)) * e1;
  out = {a.centre + y0, e1, cross(n, e1), t};
  const Partner partners[2] = {a, b};
  return verified(partners, 2, out.at(0), r) && verified(partners, 2, out.at(2.0), r);
}

PairPlane pair_plane(const Partner& a, const Partner& b, double r) {
  const Linear l = linearise(a, b, r);
  return {l.n, l.e, dot(l.n, l.n)};
}

int trilaterate(const Partner& a, const Partner& b, const Partner& c, double r,
                std::array<Vec3, 2>& out) {
  if (trilaterate(pair_plane(a, b, r), pair_plane(a, c, r), a.radius + r, out) == 0) return 0;
  out[0] = a.centre + out[0];
  out[1] = a.centre + out[1];
  return 2;
}

bool touches_all(const Partner* partners, int count, Vec3 x, double r) {
  return verified(partners, count, x, r);
}

int touch_three_3d(const Partner& a, const Partner& b, const Partner& c, double r,
                   std::array<Vec3, 2>& out) {
  if (trilaterate(a, b, c, r, out) == 0) return 0;
  const Partner partners[3] = {a, b, c};
  return keep_verified(partners, 3, r, out);
}

}  // namespace powderbed::packgen
