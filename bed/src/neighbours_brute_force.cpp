// O(N^2) reference neighbour search, for tests of the cell list and the kd-tree.
#include <cmath>

#include "neighbours_detail.hpp"
#include "powderbed/bed/neighbours.hpp"

namespace powderbed::bed {

std::vector<NeighbourPair> neighbour_pairs_brute_force(const Bed& bed, double gap) {
  detail::check_number(gap, "neighbour search: gap", false);
  detail::check_pair_index_range(bed, "neighbour search");
  std::vector<NeighbourPair> pairs;
  if (bed.n() < 2) return pairs;
  const detail::PairGeometry geometry(bed);
  const auto n = static_cast<std::uint32_t>(bed.n());
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      const double d = std::sqrt(geometry.distance2(i, j));
      if (d <= bed.radius[i] + bed.radius[j] + gap) pairs.push_back({i, j, d});
    }
  }
  return pairs;
}

}  // namespace powderbed::bed
