// Cell-list neighbour search (docs/physics.md §2, docs/architecture.md "Performance habits"): O(N) pairs.
#include <algorithm>
#include <cmath>

#include "neighbours_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/neighbours.hpp"

namespace powderbed::bed {

namespace detail {

CellList::CellList(const PairGeometry& geometry, double cutoff) : geometry_(&geometry) {
  const std::vector<double>* coords[3] = {&geometry.x, &geometry.y, &geometry.z};
  const std::size_t n = geometry.x.size();
  // Cells a hair wider than the cutoff, so that rounding in the binning never puts a pair
  // within the cutoff more than one cell apart.
  const double min_width = cutoff * (1.0 + 1e-9);
  std::array<double, 3> extent{1, 1, 1};
  for (int a = 0; a < geometry.dim; ++a) {
    origin_[a] = geometry.lower[a];
    extent[a] = geometry.length[a];
    if (!geometry.periodic[a] && n > 0) {
      // Non-periodic axes span the domain and every centre (particles may have left the box).
      const auto [lo, hi] = std::minmax_element(coords[a]->begin(), coords[a]->end());
      origin_[a] = std::min(origin_[a], *lo);
      extent[a] = std::max(geometry.lower[a] + geometry.length[a], *hi) - origin_[a];
    }
    count_[a] = static_cast<int>(std::clamp(std::floor(extent[a] / min_width), 1.0, 1048576.0));
  }
  // At most about two cells per particle: coarser cells stay >= the cutoff and keep it O(N).
  const double max_cells = 2.0 * static_cast<double>(n) + 27.0;
  while (static_cast<double>(count_[0]) * count_[1] * count_[2] > max_cells) {
    int* widest = &*std::max_element(count_.begin(), count_.end());
    *widest = std::max(1, *widest / 2);
  }
  for (int a = 0; a < 3; ++a) width_[a] = extent[a] / count_[a];

  const std::size_t total = static_cast<std::size_t>(count_[0]) * count_[1] * count_[2];
  std::vector<std::uint32_t> cell_of(n);
  start_.assign(total + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    int c[3] = {0, 0, 0};
    for (int a = 0; a < geometry.dim; ++a) {
      const double f = std::floor(((*coords[a])[i] - origin_[a]) / width_[a]);
      c[a] = static_cast<int>(std::clamp(f, 0.0, static_cast<double>(count_[a] - 1)));
    }
    cell_of[i] = static_cast<std::uint32_t>(cell_index(c[0], c[1], c[2]));
    ++start_[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < total; ++c) start_[c + 1] += start_[c];
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  order_.resize(n);
  sx_.resize(n);
  sy_.resize(n);
  sz_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t s = fill[cell_of[i]]++;
    order_[s] = static_cast<std::uint32_t>(i);
    sx_[s] = geometry.x[i];
    sy_[s] = geometry.y[i];
    sz_[s] = geometry.z[i];
  }
}

CellList::Span CellList::neighbours(int axis, int c) const {
  const int count = count_[axis];
  Span span{{0, 0, 0}, 0};
  if (geometry_->periodic[axis] && count < 3) {
    for (int k = 0; k < count; ++k) span.cells[span.size++] = k;
  } else if (geometry_->periodic[axis]) {
    span.cells = {(c + count - 1) % count, c, (c + 1) % count};
    span.size = 3;
  } else {
    for (int k = std::max(0, c - 1); k <= std::min(count - 1, c + 1); ++k) {
      span.cells[span.size++] = k;
    }
  }
  return span;
}

}  // namespace detail

std::vector<NeighbourPair> neighbour_pairs_cell_list(const Bed& bed, double gap) {
  detail::check_number(gap, "neighbour search: gap", false);
  detail::check_pair_index_range(bed, "neighbour search");
  std::vector<NeighbourPair> pairs;
  if (bed.n() < 2) return pairs;
  const detail::PairGeometry geometry(bed);
  const detail::CellList cells(geometry, 2.0 * detail::max_radius(bed) + std::max(gap, 0.0));
  const double* r = bed.radius.data();
  cells.for_each_candidate([&](std::uint32_t i, std::uint32_t j, double d2) {
    const double d = std::sqrt(d2);
    if (d <= r[i] + r[j] + gap) pairs.push_back({i, j, d});
  });
  detail::sort_pairs(pairs, bed.n());
  return pairs;
}

std::vector<NeighbourPair> pairs_within_cell_list(const Bed& bed, double cutoff) {
  detail::check_number(cutoff, "pair search: cutoff", true);
  detail::check_pair_index_range(bed, "pair search");
  std::vector<NeighbourPair> pairs;
  if (bed.n() < 2) return pairs;
  const detail::PairGeometry geometry(bed);
  const detail::CellList cells(geometry, cutoff);
  cells.for_each_candidate([&](std::uint32_t i, std::uint32_t j, double d2) {
    const double d = std::sqrt(d2);
    if (d <= cutoff) pairs.push_back({i, j, d});
  });
  detail::sort_pairs(pairs, bed.n());
  return pairs;
}

}  // namespace powderbed::bed
