#pragma once
// The simulation box as the inner loops see it: lower corner, lengths, periodic flags, and the
// minimum-image convention on periodic axes.
#include <cmath>
#include <limits>

#include "powderbed/bed/domain.hpp"

namespace powderbed::dem::detail {

struct Box {
  double lower[3] = {0, 0, 0};
  double upper[3] = {0, 0, 0};
  double length[3] = {0, 0, 0};
  bool periodic[3] = {false, false, false};

  static Box from(const bed::Domain& d) {
    Box b;
    for (int a = 0; a < 3; ++a) {
      b.lower[a] = d.lower[a];
      b.upper[a] = d.upper[a];
      b.length[a] = d.upper[a] - d.lower[a];
      b.periodic[a] = d.periodic[a];
    }
    return b;
  }
  bool any_periodic() const { return periodic[0] || periodic[1] || periodic[2]; }
  // Separation along `axis` under the minimum image on a periodic axis. Separations of wrapped
  // coordinates are shorter than the box, so one subtraction nearly always does; the general
  // rounding (a libm call without SSE4.1, a tenth of a pair's cost) is kept for the rest and
  // gives the same result bit for bit where both apply.
  double image(int axis, double delta) const {
    if (!periodic[axis]) return delta;
    const double half = 0.5 * length[axis];
    if (delta > half && delta < 1.5 * length[axis]) return delta - length[axis];
    if (delta < -half && delta > -1.5 * length[axis]) return delta + length[axis];
    if (delta >= -half && delta <= half) return delta;
    return delta - length[axis] * std::nearbyint(delta / length[axis]);
  }
  // Coordinate wrapped into [lower, upper) on a periodic axis.
  double wrap(int axis, double v) const {
    if (!periodic[axis]) return v;
    if (v < lower[axis]) return v + length[axis];
    if (v >= upper[axis]) return v - length[axis];
    return v;
  }
};

// The minimum image of the separation of two wrapped coordinates (|delta| < length on a
// periodic axis), without a branch: what Box::image gives them, for the loops that take it per
// pair or per particle every step. On other axes the shift is 0 and the bound infinite.
class WrappedImage {
 public:
  explicit WrappedImage(const Box& b) {
    for (int a = 0; a < 3; ++a) {
      shift_[a] = b.periodic[a] ? b.length[a] : 0.0;
      half_[a] = b.periodic[a] ? 0.5 * b.length[a] : std::numeric_limits<double>::infinity();
    }
  }
  double operator()(int axis, double delta) const {
    return delta - (delta > half_[axis] ? shift_[axis] : 0.0) + (delta < -half_[axis] ? shift_[axis] : 0.0);
  }

 private:
  double shift_[3], half_[3];
};

// Box::wrap for a coordinate less than a length outside the box (one step's drift), without a
// branch: for the drift loop, which must vectorise. On other axes the bounds are infinite and
// the shift 0.
class BranchFreeWrap {
 public:
  explicit BranchFreeWrap(const Box& b) {
    for (int a = 0; a < 3; ++a) {
      lower_[a] = b.periodic[a] ? b.lower[a] : -std::numeric_limits<double>::infinity();
      upper_[a] = b.periodic[a] ? b.upper[a] : std::numeric_limits<double>::infinity();
      length_[a] = b.periodic[a] ? b.length[a] : 0.0;
    }
  }
  double operator()(int axis, double v) const {
    return v + ((v < lower_[axis] ? length_[axis] : 0.0) - (v >= upper_[axis] ? length_[axis] : 0.0));
  }

 private:
  double lower_[3], upper_[3], length_[3];
};

}  // namespace powderbed::dem::detail
