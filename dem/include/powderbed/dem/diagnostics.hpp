#pragma once
// Quantities computed from a bed's state with the scene's laws: energies, wall forces,
// overlaps. Used by tests (energy conservation, floor force) and the run summary.
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>

#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::dem {

struct Energy {
  double kinetic = 0;        // sum 1/2 m v^2
  double gravitational = 0;  // sum m g (z - z_floor), when gravity is on
  double elastic = 0;        // contact energy (the scene's law) of pairs (hertz on) and walls (walls on)
  double total() const { return kinetic + gravitational + elastic; }
};
Energy energy(const bed::Bed& bed, const Scene& scene, double young_scale = 1);

// Total normal force (N, >= 0) each box face exerts on the particles, elastic plus damping
// (with the bed's velocities), indexed 2*axis + (0 lower face, 1 upper face). Faces on periodic
// axes give 0.
std::array<double, 6> wall_forces(const bed::Bed& bed, const Scene& scene, double young_scale = 1);

struct Overlap {
  double relative = 0;  // largest overlap / smaller radius of the pair (radius for walls)
  double absolute = 0;  // m
  double reduced_radius = 0;  // R* of that contact, m (r for a wall)
  bool wall = false;          // whether it is a particle–wall contact
  // Overlapping particle pairs plus (walls on) particle–box-face contacts: the contacts the
  // same pass finds.
  std::size_t contacts = 0;
};
// Largest overlap among particle pairs and (walls on) particle–wall contacts.
Overlap max_overlap(const bed::Bed& bed, const Scene& scene);
// What that overlap (relative) would be at full stiffness under the same force: the Hertz force
// goes as E delta^{3/2}, so delta_full = delta_soft * young_scale^{-2/3}; with the linear law
// the Hertz overlap at the materials' E* (of the pair or of the wall) under k_n delta
// (bed/softening.hpp).
double full_stiffness_overlap(const Overlap& overlap, const Scene& scene, double young_scale);

// Particles whose centre is outside the box on a non-periodic axis (lost), among the first `n`.
std::size_t count_outside(const bed::Bed& bed, std::size_t n);

// One row of a run's thermo table (LAMMPS's `thermo N`; deposit --thermo, docs/deposit-thermo.md).
struct ThermoRow {
  std::uint64_t step = 0;
  double time = 0;              // simulated, s
  double kinetic_energy = 0;    // J, as the progress line's
  Overlap overlap;              // max_overlap: relative overlap and contact count
  std::size_t lost = 0;         // count_outside
  std::uint64_t layer = 0;      // spreads: the layer being spread (0: a drop)
  double tool_x = std::numeric_limits<double>::quiet_NaN();  // spreads: the tool's x, m
};
using ThermoFn = std::function<void(const ThermoRow&)>;
// The overlap, contacts and lost particles of `bed`'s first `n` particles (the solvers add the
// step, time and kinetic energy they hold). Costs a neighbour-list build: call it only at the
// table's steps.
ThermoRow thermo_row(const bed::Bed& bed, const Scene& scene, std::size_t n);
// The default interval of a run of `steps` steps: about kThermoRows rows, at least 1 step.
inline constexpr std::uint64_t kThermoRows = 30;
inline std::uint64_t thermo_interval(std::uint64_t steps) {
  return std::max<std::uint64_t>(1, steps / kThermoRows);
}

// Packing density (docs/physics.md §2) of the bed's core, away from the walls' ordering and the rough
// top: the box shrunk by `margin` from the floor and from the non-periodic side faces, up to
// `margin` below the surface (the 90th percentile of the particle tops z + r, which a few
// perched particles do not move). The solid volume is counted on a grid of points (cell
// centres, spacing h = the smallest radius / 10, coarser when the core would need more than
// 2e7 points); for spheres at random offsets to the grid the count is unbiased, and its error
// over a core of many spheres is well below 1e-3 (tests/dem: a lattice of known density).
struct CoreDensity {
  double density = 0;          // NaN when the core is empty (a bed thinner than 2 margins)
  double lower[3] = {0, 0, 0};  // the core box, m
  double upper[3] = {0, 0, 0};
};
CoreDensity core_density(const bed::Bed& bed, double margin);

}  // namespace powderbed::dem
