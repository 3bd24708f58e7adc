#include "powderbed/packgen/site_heap.hpp"

#include <algorithm>

namespace powderbed::packgen {

namespace {

Vec3 direction(const Partner& a, const Partner& b) {
  return b.is_plane ? b.normal : b.centre - a.centre;
}

}  // namespace

// The side of a solution: the sign of (x - c_a) . u with u = n_ab x n_ac (n: the centre
// difference for a particle partner, the normal for a plane), which does not depend on r.
bool site_centre(const Partner& a, const Partner& b, const Partner& c, double r,
                 std::uint8_t side, Vec3& x) {
  std::array<Vec3, 2> out;
  const int m = touch_three_3d(a, b, c, r, out);
  Vec3 u = cross(direction(a, b), direction(a, c));
  u = (1.0 / norm(u)) * u;
  // A point within kTangent (relative) of the axis (a tangent pair) counts for both sides.
  constexpr double kTangent = 1e-9;
  const double tol = kTangent * (a.radius + r);
  for (int k = 0; k < m; ++k) {
    const Vec3 p = out[static_cast<std::size_t>(k)];
    const double s = dot(p - a.centre, u);
    if (side == 0 ? s >= -tol : s <= tol) {
      x = p;
      return true;
    }
  }
  return false;
}

}  // namespace powderbed::packgen
