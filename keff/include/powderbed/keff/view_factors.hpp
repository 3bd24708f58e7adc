#pragma once
// Monte-Carlo view factors of a bed between the two isothermal walls (docs/physics.md §6, radiation).
// Rays leave uniform random points of each sphere's surface (Marsaglia's method) in
// cosine-weighted directions about the outward normal (diffuse emission; [KE] drew uniform
// hemisphere directions, which over-weights grazing rays). F_ij is the fraction of i's rays whose
// first hit is sphere j or one of the walls. The hot and cold walls (the faces of `axis`) absorb
// every ray; the four side faces are specular mirrors (an adiabatic face reflects what it gets,
// and a mirror keeps the box closed so every row sums to 1; where the bed is periodic the mirror
// image stands in for the periodic image). A point of i's surface inside an overlapping sphere j
// (or beyond a wall) is not free surface: its ray hits j (the wall) at once, which keeps
// A_i F_ij = A_j F_ji for overlapping pairs to first order in the overlap.
//
// The walls see each other where the bed leaves a gap: F_wall (hot to cold, equal to cold to hot
// for the equal areas) is the fraction of rays from uniform points of each wall, in
// cosine-weighted directions into the box, that reach the other wall; each wall sends
// `rays` × ⌈A_wall / A_sphere⌉ of them (A_sphere of the mean radius), as many as spheres of its
// area would, at most kMaxWallRays (the binomial error of F_wall is then below 5e-4; in a bed
// a few diameters thick no ray crosses and F_wall = 0 exactly).
//
// Rays are traced with the project's one ray–sphere tracer (powderbed/bed/ray_trace.hpp: a
// uniform grid of cells holding every sphere that overlaps them). Particle i draws from its own
// random stream seeded by (seed, i), so the result does not depend on the number of threads.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/keff/network.hpp"

namespace powderbed::keff {

struct ViewFactorParams {
  std::size_t rays = 1000;  // rays per particle
  std::uint64_t seed = 1;
  int axis = 2;             // the walls are the faces of this axis: hot upper, cold lower
  // Called now and then with the fraction of particles traced (from one thread only); empty:
  // no calls. The tracing is the long part of a keff run with radiation.
  std::function<void(double)> progress;
};

struct ViewFactorEntry {
  std::uint32_t i;  // emitting particle
  std::uint32_t j;  // particle hit (j == i: itself, seen in a side mirror), kHotWall or kColdWall
  double f;         // fraction of i's rays, > 0
};

struct ViewFactors {
  std::vector<ViewFactorEntry> entries;  // sorted by i, then j
  std::size_t rays = 0;                  // per particle
  std::size_t lost_rays = 0;  // rays still bouncing between the mirrors after kMaxReflections
  double wall_to_wall = 0;    // F between the two walls (mean of both directions)
};

inline constexpr int kMaxReflections = 1000;
inline constexpr double kMaxWallRays = 1e6;

// Throws InputError for rays = 0 or a 2D bed.
ViewFactors view_factors(const bed::Bed& bed, const ViewFactorParams& params);

}  // namespace powderbed::keff
