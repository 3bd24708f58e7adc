#pragma once
// Small beds built in code for the dem tests.
#include <cmath>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::test {

// Whether a sphere of radius r at p overlaps no particle of b (brute force: test beds are small).
inline bool is_free(const bed::Bed& b, const double p[3], double r) {
  for (std::size_t j = 0; j < b.n(); ++j) {
    const double dx = b.x[j] - p[0], dy = b.y[j] - p[1], dz = b.z[j] - p[2];
    if (dx * dx + dy * dy + dz * dz <= (r + b.radius[j]) * (r + b.radius[j])) return false;
  }
  return true;
}

inline bed::Bed box_bed(double lx, double ly, double lz) {
  bed::Bed b;
  b.domain.dimension = 3;
  b.domain.upper = {lx, ly, lz};
  return b;
}

// Adds a particle with a velocity (the bed gets velocity arrays).
inline void add_moving(bed::Bed& b, double x, double y, double z, double r, double vx, double vy,
                       double vz) {
  b.add(x, y, z, r);
  b.vx.resize(b.n() - 1);
  b.vy.resize(b.n() - 1);
  b.vz.resize(b.n() - 1);
  b.vx.push_back(vx);
  b.vy.push_back(vy);
  b.vz.push_back(vz);
}

// `count` non-overlapping particles of radii in [r0, r1] at uniform random positions inside the
// box region [lo, hi] (fixed seed; brute-force rejection, fine for the few hundred used here).
inline void add_random(bed::Bed& b, std::size_t count, double r0, double r1, const double lo[3],
                       const double hi[3], std::uint64_t seed) {
  bed::Rng rng(seed);
  std::size_t placed = 0;
  while (placed < count) {
    const double r = bed::uniform(rng, r0, r1);
    const double p[3] = {bed::uniform(rng, lo[0] + r, hi[0] - r),
                         bed::uniform(rng, lo[1] + r, hi[1] - r),
                         bed::uniform(rng, lo[2] + r, hi[2] - r)};
    if (!is_free(b, p, r)) continue;
    b.add(p[0], p[1], p[2], r);
    ++placed;
  }
}

// Up to `count` non-overlapping particles with radii drawn from `psd`, x and y uniform inside the
// box, the lowest point uniform in [0, max_gap] above the floor (a drop from a low height).
// Brute-force rejection, giving up after `max_tries` draws; returns how many were placed.
inline std::size_t add_near_floor(bed::Bed& b, std::size_t count, const bed::Psd& psd,
                                  double max_gap, std::uint64_t seed,
                                  std::size_t max_tries = 100000) {
  bed::Rng rng(seed);
  std::size_t placed = 0;
  for (std::size_t tries = 0; placed < count && tries < max_tries; ++tries) {
    const double r = psd.sample_radius(rng);
    const double p[3] = {bed::uniform(rng, r, b.domain.upper[0] - r),
                         bed::uniform(rng, r, b.domain.upper[1] - r),
                         bed::uniform(rng, r, r + max_gap)};
    if (!is_free(b, p, r)) continue;
    b.add(p[0], p[1], p[2], r);
    ++placed;
  }
  return placed;
}

// A scene with only the given effects on; 316L of [GZ] Table 2 otherwise.
inline dem::Scene scene_with(unsigned effects) {
  dem::Scene s;
  s.effects = effects;
  return s;
}

inline double sphere_mass(double r, double density) {
  return 4.0 / 3.0 * 3.14159265358979323846 * r * r * r * density;
}

}  // namespace powderbed::test
