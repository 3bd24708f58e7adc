#pragma once
// Quantities computed from a bed's state with the scene's laws: energies, wall forces,
// overlaps. Used by tests (energy conservation, floor force) and the run summary.
#include <array>

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
};
// Largest overlap among particle pairs and (walls on) particle–wall contacts.
Overlap max_overlap(const bed::Bed& bed, const Scene& scene);

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
