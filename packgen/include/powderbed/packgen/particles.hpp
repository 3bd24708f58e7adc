#pragma once
// The particles placed so far (structure of arrays) and the one exact overlap predicate that
// every exact collision back-end shares, so that they answer bit for bit alike (docs/physics.md §3).
#include <cstdint>
#include <vector>

namespace powderbed::packgen {

struct Particles {
  std::vector<double> x, y, z, r;  // centres and radii, m (2D: z = 0)
  std::uint32_t size() const { return static_cast<std::uint32_t>(r.size()); }
};

// Relative tolerance of the exact tests (docs/physics.md §3 "exact overlap tests with a small
// tolerance"): a pair overlaps when d < (r_i + r_j)(1 - kTouchTolerance). Touching solutions
// carry rounding errors of ~1e-15 relative, far below this, so they are accepted; an accepted
// pair can overlap by at most 1e-12 relative, far below the 1e-9 that the tests allow.
constexpr double kTouchTolerance = 1e-12;

// d^2 < s^2 (1 - tol)^2 with (1 - tol)^2 ~ 1 - 2 tol.
inline bool overlaps(double dx, double dy, double dz, double radius_sum) {
  return dx * dx + dy * dy + dz * dz < radius_sum * radius_sum * (1.0 - 2.0 * kTouchTolerance);
}

}  // namespace powderbed::packgen
