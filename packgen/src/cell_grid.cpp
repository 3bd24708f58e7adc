#include "powderbed/packgen/cell_grid.hpp"

namespace powderbed::packgen {

namespace {

std::size_t cell_count(const bed::Domain& domain, double cell) {
  std::size_t n = 1;
  for (int a = 0; a < domain.dimension; ++a) {
    n *= static_cast<std::size_t>(std::max(1.0, std::ceil(domain.length(a) / cell)));
  }
  return n;
}

}  // namespace

CellGrid::CellGrid(const bed::Domain& domain, double r_min, double r_max,
                   const Particles& particles, std::size_t max_cells)
    : p_(particles), dimension_(domain.dimension), lower_(domain.lower) {
  // Level count: cells 2 r_max / 2^k down to no finer than 2 r_min, and within max_cells.
  int finest = 0;
  while (2 * r_max / std::ldexp(1.0, finest + 1) >= 2 * r_min &&
         cell_count(domain, 2 * r_max / std::ldexp(1.0, finest + 1)) <= max_cells) {
    ++finest;
  }
  // The coarsest level must fit in memory too: grow its cell when the domain is huge.
  double top = 2 * r_max;
  while (cell_count(domain, top) > max_cells) top *= 2;
  for (int k = 0; k <= finest; ++k) {
    Level level;
    level.cell = top / std::ldexp(1.0, k);
    level.inv_cell = 1.0 / level.cell;
    for (int a = 0; a < dimension_; ++a) {
      level.n[a] = static_cast<int>(std::max(1.0, std::ceil(domain.length(a) / level.cell)));
    }
    level.head.assign(cell_count(domain, level.cell), -1);
    levels_.push_back(std::move(level));
  }
}

void CellGrid::insert(std::uint32_t i) {
  if (next_.size() <= i) next_.resize(std::max<std::size_t>(i + 1, 2 * next_.size()), -1);
  const double d = 2 * p_.r[i];
  std::size_t k = levels_.size() - 1;  // finest level whose cell holds the diameter
  while (k > 0 && levels_[k].cell < d) --k;
  Level& level = levels_[k];
  const double c[3] = {p_.x[i], p_.y[i], p_.z[i]};
  std::size_t index = 0, stride = 1;
  for (int a = 0; a < dimension_; ++a) {
    const double f = std::floor((c[a] - lower_[a]) * level.inv_cell);
    const int cell = static_cast<int>(std::min(std::max(f, 0.0), double(level.n[a] - 1)));
    index += static_cast<std::size_t>(cell) * stride;
    stride *= static_cast<std::size_t>(level.n[a]);
  }
  next_[i] = level.head[index];
  level.head[index] = static_cast<std::int32_t>(i);
  level.r_max_inserted = std::max(level.r_max_inserted, p_.r[i]);
}

bool CellGrid::fits(double x, double y, double z, double r, std::int64_t after) const {
  for (const Level& level : levels_) {
    if (level.r_max_inserted == 0) continue;
    const bool hit = scan(level, x, y, z, r + level.r_max_inserted, [&](std::uint32_t j) {
      return overlaps(p_.x[j] - x, p_.y[j] - y, p_.z[j] - z, p_.r[j] + r);
    }, after);
    if (hit) return false;
  }
  return true;
}

}  // namespace powderbed::packgen
