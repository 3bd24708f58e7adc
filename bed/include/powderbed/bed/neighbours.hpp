#pragma once
// Neighbour search over a bed: a cell list (cells sized from the largest particle) and a
// nanoflann kd-tree, both answering the same two questions. Periodic axes use the minimum image.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "powderbed/bed/bed.hpp"

namespace powderbed::bed {

struct NeighbourPair {
  std::uint32_t i, j;  // i < j
  double distance;     // centre distance (minimum image)
};

// All pairs with centre distance <= r_i + r_j + gap, sorted by (i, j).
std::vector<NeighbourPair> neighbour_pairs_cell_list(const Bed& bed, double gap);
std::vector<NeighbourPair> neighbour_pairs_kdtree(const Bed& bed, double gap);
std::vector<NeighbourPair> neighbour_pairs_brute_force(const Bed& bed, double gap);

// All pairs with centre distance <= cutoff (independent of radii), sorted; for g(r).
std::vector<NeighbourPair> pairs_within_cell_list(const Bed& bed, double cutoff);

}  // namespace powderbed::bed
