#pragma once
// Verlet neighbour list built from a cell list (SPEC §4 "neighbour search by binning"): every
// particle gets the full list of partners (both directions) within r_i + r_j + skin, so forces
// are summed per particle in a fixed order for any thread count. Cells are at least the largest
// diameter plus the skin wide, so one build costs O(N); the list is rebuilt when some particle
// has moved more than skin/2 since the last build.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "box.hpp"

namespace powderbed::dem::detail {

struct ParticleView {
  const double* x;
  const double* y;
  const double* z;
  const double* radius;
  std::size_t n;
};

class NeighbourList {
 public:
  // Fixes the geometry for n particles: cell size >= 2 r_max + skin. Throws InputError when a
  // periodic axis is shorter than 3 cells (the minimum image would then miss or repeat partners).
  void configure(const Box& box, double r_max, double skin, std::size_t n);
  void build(const ParticleView& p, int threads);
  // Largest squared displacement since the last build, under the minimum image.
  double max_displacement2(const ParticleView& p, int threads) const;
  double skin() const { return skin_; }

  const std::uint32_t* begin(std::size_t i) const { return partners_.data() + offset_[i]; }
  const std::uint32_t* end(std::size_t i) const { return partners_.data() + offset_[i + 1]; }
  std::size_t pair_entries() const { return partners_.size(); }

 private:
  template <class F>
  void for_each_candidate(const ParticleView& p, std::size_t i, F&& f) const;
  int cell_coordinate(int axis, double v) const;

  Box box_;
  double skin_ = 0;
  int cells_[3] = {1, 1, 1};
  double cell_size_[3] = {1, 1, 1};
  std::vector<std::uint32_t> cell_start_;     // size cells + 1
  std::vector<std::uint32_t> cell_particles_; // particle indices sorted by cell, then index
  std::vector<std::uint32_t> particle_cell_;  // flat cell index per particle
  std::vector<std::uint32_t> offset_;         // size n + 1
  std::vector<std::uint32_t> partners_;
  std::vector<double> x0_, y0_, z0_;          // positions at the last build
};

}  // namespace powderbed::dem::detail
