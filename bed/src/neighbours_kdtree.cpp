// kd-tree neighbour search (nanoflann 1.4 radius search), the alternative back-end to the cell
// list of docs/physics.md §2. Periodic axes: a particle within the search radius of a periodic face also
// queries its image shifted by one period; candidates are then measured at the minimum image.
#include <algorithm>
#include <array>
#include <cmath>
#include <nanoflann.hpp>
#include <utility>

#include "neighbours_detail.hpp"
#include "powderbed/bed/neighbours.hpp"

namespace powderbed::bed {

namespace {

// nanoflann dataset adaptor over the wrapped centres.
struct CentreCloud {
  const detail::PairGeometry* g;
  std::size_t kdtree_get_point_count() const { return g->x.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t axis) const {
    return axis == 0 ? g->x[i] : axis == 1 ? g->y[i] : g->z[i];
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

template <int Dim>
std::vector<NeighbourPair> kdtree_pairs(const Bed& bed, const detail::PairGeometry& g,
                                        double gap) {
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<
      nanoflann::L2_Simple_Adaptor<double, CentreCloud>, CentreCloud, Dim, std::size_t>;
  const CentreCloud cloud{&g};
  Tree tree(Dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  const double search = 2.0 * detail::max_radius(bed) + std::max(gap, 0.0);
  // nanoflann compares squared distances strictly; widen a hair, the exact test follows.
  const double search2 = search * search * (1.0 + 1e-9);
  const nanoflann::SearchParams params(32, 0.0f, false);
  std::vector<std::pair<std::size_t, double>> matches;
  std::vector<std::size_t> candidates;
  std::vector<NeighbourPair> pairs;
  const std::size_t n = bed.n();
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<double, 3> centre{g.x[i], g.y[i], g.z[i]};
    // Shifts per axis: 0, and +-length near a periodic face.
    std::array<std::array<double, 3>, Dim> shifts{};
    std::array<int, Dim> count{};
    for (int a = 0; a < Dim; ++a) {
      shifts[a][count[a]++] = 0.0;
      if (!g.periodic[a]) continue;
      if (centre[a] - g.lower[a] < search) shifts[a][count[a]++] = g.length[a];
      if (g.lower[a] + g.length[a] - centre[a] < search) shifts[a][count[a]++] = -g.length[a];
    }
    candidates.clear();
    std::array<int, 3> k{0, 0, 0};
    const int z_shifts = Dim == 3 ? count[Dim - 1] : 1;
    for (k[2] = 0; k[2] < z_shifts; ++k[2]) {
      for (k[1] = 0; k[1] < count[1]; ++k[1]) {
        for (k[0] = 0; k[0] < count[0]; ++k[0]) {
          double query[Dim];
          for (int a = 0; a < Dim; ++a) query[a] = centre[a] + shifts[a][k[a]];
          tree.radiusSearch(query, search2, matches, params);
          for (const auto& m : matches) {
            if (m.first > i) candidates.push_back(m.first);
          }
        }
      }
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (const std::size_t j : candidates) {
      const double d = std::sqrt(g.distance2(i, j));
      if (d <= bed.radius[i] + bed.radius[j] + gap) {
        pairs.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), d});
      }
    }
  }
  return pairs;
}

}  // namespace

std::vector<NeighbourPair> neighbour_pairs_kdtree(const Bed& bed, double gap) {
  detail::check_number(gap, "neighbour search: gap", false);
  detail::check_pair_index_range(bed, "neighbour search");
  if (bed.n() < 2) return {};
  const detail::PairGeometry geometry(bed);
  return geometry.dim == 3 ? kdtree_pairs<3>(bed, geometry, gap)
                           : kdtree_pairs<2>(bed, geometry, gap);
}

}  // namespace powderbed::bed
