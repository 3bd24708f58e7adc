#pragma once
// Verlet neighbour list built from a cell list (docs/physics.md §4 "neighbour search by binning"): a half
// list, each pair (i, j) within r_i + r_j + skin once, under its lower index i, so each contact
// force is computed once. For a deterministic parallel sum each particle also gets its incident
// pairs in a fixed order (the pairs under lower indices, by that index, then its own), the order
// in which a serial loop over i that adds F to i and subtracts it from j meets them. Cells are
// at least the largest diameter plus the skin wide, so one build costs O(N); the list is rebuilt
// when some particle has moved more than skin/2 since the last build (moved_more_than), or, with
// pruning (the spread), as `stale` says.
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
  // Builds the half list; with_incident also builds the incident lists (parallel force sums).
  // Only particles below `owners` own pairs: those above it (frozen, spread.cpp) are partners
  // of the ones below and have no pairs among themselves.
  void build(const ParticleView& p, int threads, bool with_incident = false,
             std::size_t owners = static_cast<std::size_t>(-1));
  // Whether some particle moved more than `limit` since the last build (minimum image).
  bool moved_more_than(const ParticleView& p, double limit, int threads) const;
  double skin() const { return skin_; }

  // Dynamic pruning, as GROMACS's outer and inner pair lists (rlistOuter, rlistInner;
  // Pall et al. 2020, J. Chem. Phys. 153, 134110), but on a measured displacement where GROMACS
  // prunes at a fixed interval: the entries whose separation is within r_i + r_j + margin
  // ("hot", in entry order), for a force loop to scan instead of them all. No other entry can
  // touch while no particle has moved more than margin / 2 since the prune. Serial; wrapped
  // positions.
  void prune(const ParticleView& p, double margin);
  const std::uint32_t* hot() const { return hot_.data(); }
  std::size_t hot_entries() const { return hot_.size(); }
  // What the particles' motion asks for: nothing while none has moved more than margin / 2
  // since the last prune (one pass over them, every step); else a build if one has moved more
  // than (skin - margin) / 2 since the last build, so that the list holds until the next
  // prune (a second pass), else a prune.
  enum class Stale { no, prune, build };
  Stale stale(const ParticleView& p) const;

  const std::uint32_t* begin(std::size_t i) const { return partners_.data() + offset_[i]; }
  const std::uint32_t* end(std::size_t i) const { return partners_.data() + offset_[i + 1]; }
  std::size_t pair_entries() const { return partners_.size(); }
  // Pair k as (owner(k), partner(k)): the lower and the upper index, for loops over all pairs
  // with no inner loop per particle (whose varying trip counts the branch predictor misses).
  const std::uint32_t* owners() const { return owners_.data(); }
  const std::uint32_t* partners() const { return partners_.data(); }
  // Index of i's first pair: begin(i)[m] is pair offset(i) + m (per-pair tables use it).
  std::size_t offset(std::size_t i) const { return offset_[i]; }
  // Incident pairs of particle i: 2 k + 1 when i is the pair's lower index (force on i is +F_k),
  // 2 k when it is the upper one (-F_k).
  const std::uint32_t* incident_begin(std::size_t i) const { return incident_.data() + incident_offset_[i]; }
  const std::uint32_t* incident_end(std::size_t i) const { return incident_.data() + incident_offset_[i + 1]; }

 private:
  template <class F>
  void for_each_candidate(const ParticleView& p, std::size_t i, F&& f) const;
  int cell_coordinate(int axis, double v) const;
  void fill_in_parallel(const ParticleView& p, int threads, std::size_t owners);

  Box box_;
  double skin_ = 0;
  int cells_[3] = {1, 1, 1};
  double cell_size_[3] = {1, 1, 1};
  std::vector<std::uint32_t> cell_start_;     // size cells + 1
  std::vector<std::uint32_t> cell_particles_; // particle indices sorted by cell, then index
  std::vector<std::uint32_t> particle_cell_;  // flat cell index per particle
  // x, y, z, r of cell_particles_[s] at 4 s: a cell's candidates read in one sweep of memory
  // rather than gathered from the particle arrays.
  std::vector<double> sorted_;
  std::vector<std::uint32_t> offset_;         // size n + 1
  std::vector<std::uint32_t> partners_;
  std::vector<std::uint32_t> owners_;         // per pair: its lower index
  std::vector<std::uint32_t> incident_offset_;  // size n + 1 (with_incident)
  std::vector<std::uint32_t> incident_;
  std::vector<double> x0_, y0_, z0_;          // positions at the last build
  std::vector<std::uint32_t> hot_;            // prune: the entries within reach + margin_
  double margin_ = 0;
  std::vector<double> xp_, yp_, zp_;          // positions at the last prune
};

}  // namespace powderbed::dem::detail
