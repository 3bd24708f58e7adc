#pragma once
// The simulation box shared by every stage (docs/bed-format.md, /domain).
#include <array>
#include <vector>

namespace powderbed::bed {

struct Domain {
  int dimension = 3;                       // 2 (disks in the z = 0 plane) or 3
  std::array<double, 3> lower{0, 0, 0};    // m
  std::array<double, 3> upper{1, 1, 1};    // m; in 2D upper[2] == lower[2] == 0
  std::array<bool, 3> periodic{false, false, false};

  double length(int axis) const { return upper[axis] - lower[axis]; }
  // Area in 2D, volume in 3D.
  double measure() const {
    double m = length(0) * length(1);
    return dimension == 3 ? m * length(2) : m;
  }
  // Throws InputError (naming `what`) unless lower < upper on every used axis and dimension is 2/3.
  void validate(const char* what = "domain") const;
};

// The box [0, L] of 2 or 3 lengths (packgen's and deposit's --domain LX,LY[,LZ], Python's
// pack(domain=...)), its dimension their count; throws InputError naming `what` for another
// count or a length that is not > 0.
Domain box_of_lengths(const std::vector<double>& lengths, const char* what);

}  // namespace powderbed::bed
