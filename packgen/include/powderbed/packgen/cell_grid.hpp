#pragma once
// Exact collision back-end and partner index: a hierarchical uniform cell list (docs/physics.md §3,
// "a hashed/multi-level grid for wide PSDs"). Level k has cells of size 2 r_max / 2^k; a particle
// lives in the finest level whose cells are at least its diameter, so a small particle never
// scans cells sized for the largest one. A monodisperse or narrow PSD (r_max / r_min < 2) gets
// one level with cell = the largest diameter. Cells are singly linked lists (head per cell,
// next per particle): inserting allocates nothing once the particle arrays have grown.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "powderbed/bed/domain.hpp"
#include "powderbed/packgen/particles.hpp"

namespace powderbed::packgen {

class CellGrid {
 public:
  // `max_cells` bounds the finest level's cell count (coarser cells beyond it).
  CellGrid(const bed::Domain& domain, double r_min, double r_max, const Particles& particles,
           std::size_t max_cells = std::size_t{1} << 24);

  void insert(std::uint32_t i);
  // True when a sphere (disk) of radius r at (x, y, z) overlaps no inserted particle with an
  // index above `after` (-1: every particle). A cell's list runs newest first, so its walk
  // stops at the first particle at or below `after`.
  bool fits(double x, double y, double z, double r, std::int64_t after = -1) const;
  // Calls f(j) for every inserted j with |c_j - c| <= r_j + extra; f returns true to stop.
  template <class F>
  void for_each_within(double x, double y, double z, double extra, F&& f) const;

  std::size_t levels() const { return levels_.size(); }

 private:
  struct Level {
    double cell = 0, inv_cell = 0;
    std::array<int, 3> n{1, 1, 1};
    std::vector<std::int32_t> head;  // first particle per cell, -1 when empty
    double r_max_inserted = 0;       // 0 while empty
  };
  // Calls f(j) for the particles j > after of every cell of `level` meeting the box c +- reach,
  // until f returns true; returns true when stopped.
  template <class F>
  bool scan(const Level& level, double x, double y, double z, double reach, F&& f,
            std::int64_t after = -1) const;
  int cell_range(const Level& level, int axis, double c, double reach, int& hi) const;

  const Particles& p_;
  int dimension_;
  std::array<double, 3> lower_;
  std::vector<Level> levels_;
  std::vector<std::int32_t> next_;
};

inline int CellGrid::cell_range(const Level& level, int axis, double c, double reach,
                                int& hi) const {
  const double n = level.n[axis] - 1;
  const double a = std::floor((c - reach - lower_[axis]) * level.inv_cell);
  const double b = std::floor((c + reach - lower_[axis]) * level.inv_cell);
  hi = static_cast<int>(std::min(std::max(b, 0.0), n));
  return static_cast<int>(std::min(std::max(a, 0.0), n));
}

template <class F>
bool CellGrid::scan(const Level& level, double x, double y, double z, double reach, F&& f,
                    std::int64_t after) const {
  int x1 = 0, y1 = 0, z1 = 0;
  const int x0 = cell_range(level, 0, x, reach, x1);
  const int y0 = cell_range(level, 1, y, reach, y1);
  int z0 = 0;
  if (dimension_ == 3) z0 = cell_range(level, 2, z, reach, z1);
  const std::size_t nx = static_cast<std::size_t>(level.n[0]);
  const std::size_t nxy = nx * static_cast<std::size_t>(level.n[1]);
  for (int k = z0; k <= z1; ++k) {
    for (int j = y0; j <= y1; ++j) {
      const std::size_t row = static_cast<std::size_t>(k) * nxy + static_cast<std::size_t>(j) * nx;
      for (int i = x0; i <= x1; ++i) {
        // The list ends with -1, which is never above `after` (>= -1).
        for (std::int32_t q = level.head[row + static_cast<std::size_t>(i)]; q > after;
             q = next_[q]) {
          if (f(static_cast<std::uint32_t>(q))) return true;
        }
      }
    }
  }
  return false;
}

template <class F>
void CellGrid::for_each_within(double x, double y, double z, double extra, F&& f) const {
  for (const Level& level : levels_) {
    if (level.r_max_inserted == 0) continue;
    const bool stopped = scan(level, x, y, z, extra + level.r_max_inserted, [&](std::uint32_t j) {
      const double dx = p_.x[j] - x, dy = p_.y[j] - y, dz = p_.z[j] - z;
      const double s = p_.r[j] + extra;
      return dx * dx + dy * dy + dz * dz <= s * s ? f(j) : false;
    });
    if (stopped) return;
  }
}

}  // namespace powderbed::packgen
