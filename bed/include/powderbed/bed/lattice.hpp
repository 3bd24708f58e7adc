#pragma once
// Reference lattice beds with closed-form statistics (tests, the README's first job).
#include "powderbed/bed/bed.hpp"

namespace powderbed::bed {

// n x n x n touching spheres of radius r, simple cubic, in the box [0, 2 n r]^3 (phi = pi/6).
Bed simple_cubic_lattice(int n, double r);
// n x n x n conventional FCC cells (4 n^3 touching spheres) in [0, n a]^3, a = 2 sqrt(2) r,
// periodic on all axes (phi = pi / (3 sqrt 2), Z = 12).
Bed fcc_lattice(int n, double r);
// 2D hexagonal disks: nx columns x ny rows (ny even), periodic box (phi = pi / (2 sqrt 3), Z = 6).
Bed hexagonal_lattice_2d(int nx, int ny, double r);

}  // namespace powderbed::bed
