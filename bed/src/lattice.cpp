#include "powderbed/bed/lattice.hpp"

#include <cmath>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

Bed simple_cubic_lattice(int n, double r) {
  if (n < 1 || !(r > 0)) throw InputError("simple cubic lattice: needs n >= 1 and r > 0");
  Bed bed;
  bed.domain.dimension = 3;
  const double side = 2.0 * r * n;
  bed.domain.upper = {side, side, side};
  bed.reserve(static_cast<std::size_t>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) bed.add((2 * i + 1) * r, (2 * j + 1) * r, (2 * k + 1) * r, r);
  bed.provenance.stage = "lattice";
  return bed;
}

Bed fcc_lattice(int n, double r) {
  if (n < 1 || !(r > 0)) throw InputError("fcc lattice: needs n >= 1 and r > 0");
  const double a = 2.0 * std::sqrt(2.0) * r;  // nearest-neighbour distance a / sqrt 2 = 2 r
  Bed bed;
  bed.domain.dimension = 3;
  bed.domain.upper = {n * a, n * a, n * a};
  bed.domain.periodic = {true, true, true};
  static const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  // Offset by a/4 so no centre sits exactly on a periodic face.
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& b : basis)
          bed.add((i + b[0] + 0.25) * a, (j + b[1] + 0.25) * a, (k + b[2] + 0.25) * a, r);
  bed.provenance.stage = "lattice";
  return bed;
}

Bed hexagonal_lattice_2d(int nx, int ny, double r) {
  if (nx < 1 || ny < 2 || ny % 2 != 0 || !(r > 0))
    throw InputError("hexagonal lattice: needs nx >= 1, even ny >= 2 and r > 0");
  const double row = std::sqrt(3.0) * r;  // row spacing of touching disks
  Bed bed;
  bed.domain.dimension = 2;
  bed.domain.upper = {2.0 * r * nx, row * ny, 0.0};
  bed.domain.periodic = {true, true, false};
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      bed.add((2 * i + 0.5 + (j % 2)) * r, (j + 0.5) * row, 0.0, r);
  bed.provenance.stage = "lattice";
  return bed;
}

}  // namespace powderbed::bed
