#pragma once
// Private to libbed: the one pair geometry (wrapped coordinates, minimum image) every neighbour
// search shares, so that the cell list, the kd-tree and brute force give bit-identical distances,
// and the cell list itself (a counting sort of particles by cell) that the statistics traverse
// without building a pair list.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/neighbours.hpp"

namespace powderbed::bed::detail {

// Particle centres wrapped into [lower, upper) on periodic axes (unchanged elsewhere) and the
// minimum-image rule. dim = 2 ignores z.
struct PairGeometry {
  int dim = 3;
  std::array<double, 3> lower{0, 0, 0};
  std::array<double, 3> length{0, 0, 0};
  std::array<double, 3> half{0, 0, 0};
  std::array<bool, 3> periodic{false, false, false};
  std::vector<double> x, y, z;  // wrapped centres, by particle index

  explicit PairGeometry(const Bed& bed);

  // Minimum-image component of b - a on `axis`; exactly antisymmetric in (a, b).
  double delta(int axis, double a, double b) const {
    double d = b - a;
    if (periodic[axis]) {
      if (d > half[axis]) {
        d -= length[axis];
      } else if (d < -half[axis]) {
        d += length[axis];
      }
    }
    return d;
  }
  // Squared minimum-image centre distance of particles i and j.
  double distance2(std::size_t i, std::size_t j) const {
    const double dx = delta(0, x[i], x[j]);
    const double dy = delta(1, y[i], y[j]);
    const double dz = dim == 3 ? delta(2, z[i], z[j]) : 0.0;
    return dx * dx + dy * dy + dz * dz;
  }
};

// Throws InputError unless the bed has fewer than 2^32 particles (NeighbourPair indices).
void check_pair_index_range(const Bed& bed, const char* what);
// Throws InputError naming `what` unless value is finite (and > 0 when `positive`).
void check_number(double value, const char* what, bool positive);
// Largest radius (0 for an empty bed).
double max_radius(const Bed& bed);
// Sorts pairs by (i, j) in O(N + P): counting sort on i, then the few j of each i.
void sort_pairs(std::vector<NeighbourPair>& pairs, std::size_t n);

// Uniform cells of width >= cutoff over the domain (widened to the particles' extent on
// non-periodic axes), particles counting-sorted by cell. Periodic axes with fewer than 3 cells
// visit every cell of the axis once, so small periodic boxes are still searched correctly
// (at the minimum image).
class CellList {
 public:
  CellList(const PairGeometry& geometry, double cutoff);

  // Calls f(i, j, d2) once for every pair i < j in the same or adjacent cells, d2 the squared
  // minimum-image distance. Every pair with distance <= cutoff is visited; others may be.
  template <class F>
  void for_each_candidate(F&& f) const {
    const PairGeometry& g = *geometry_;
    for (int cz = 0; cz < count_[2]; ++cz) {
      for (int cy = 0; cy < count_[1]; ++cy) {
        for (int cx = 0; cx < count_[0]; ++cx) {
          const std::size_t home = cell_index(cx, cy, cz);
          const Span nx = neighbours(0, cx), ny = neighbours(1, cy), nz = neighbours(2, cz);
          for (std::uint32_t s = start_[home]; s < start_[home + 1]; ++s) {
            const std::uint32_t i = order_[s];
            const double xi = sx_[s], yi = sy_[s], zi = sz_[s];
            for (int a = 0; a < nz.size; ++a) {
              for (int b = 0; b < ny.size; ++b) {
                for (int c = 0; c < nx.size; ++c) {
                  const std::size_t cell = cell_index(nx.cells[c], ny.cells[b], nz.cells[a]);
                  for (std::uint32_t t = start_[cell]; t < start_[cell + 1]; ++t) {
                    const std::uint32_t j = order_[t];
                    if (j <= i) continue;
                    const double dx = g.delta(0, xi, sx_[t]);
                    const double dy = g.delta(1, yi, sy_[t]);
                    const double dz = g.dim == 3 ? g.delta(2, zi, sz_[t]) : 0.0;
                    f(i, j, dx * dx + dy * dy + dz * dz);
                  }
                }
              }
            }
          }
        }
      }
    }
  }

 private:
  struct Span {
    std::array<int, 3> cells;
    int size;
  };
  std::size_t cell_index(int cx, int cy, int cz) const {
    return (static_cast<std::size_t>(cz) * count_[1] + cy) * count_[0] + cx;
  }
  Span neighbours(int axis, int c) const;

  const PairGeometry* geometry_;
  std::array<int, 3> count_{1, 1, 1};
  std::array<double, 3> origin_{0, 0, 0};
  std::array<double, 3> width_{1, 1, 1};
  std::vector<std::uint32_t> start_;   // cells + 1 offsets into order_
  std::vector<std::uint32_t> order_;   // particle indices sorted by cell
  std::vector<double> sx_, sy_, sz_;   // wrapped centres in cell order
};

}  // namespace powderbed::bed::detail
