#pragma once
// Rays among the spheres of a bed: the one tracer of the project, shared by keff's Monte-Carlo
// view factors and sinter's ray-traced laser absorption.
//
// - SphereGrid: a uniform grid of cells over the bed's domain grown by the largest radius, each
//   cell listing every sphere whose bounding box overlaps it; first_hit walks the cells along
//   the ray (Amanatides & Woo 1987) and stops once no later cell can hold a nearer hit.
// - RandomStream: SplitMix64 (Steele, Lea & Flood 2014), a generator whose output is the same on
//   every platform (std:: distributions are not), seeded per task so threads do not matter.
// - Directions: uniform on the sphere (Marsaglia 1972), cosine-weighted about a normal (Lambert),
//   and the specular reflection.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "powderbed/bed/bed.hpp"

namespace powderbed::bed {

using Vec3 = std::array<double, 3>;

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint64_t task)
      : state_(seed * 0x9E3779B97F4A7C15ULL ^ (task + 1) * 0xD1B54A32D192ED03ULL) {
    next();
  }
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  std::uint64_t state_;
};

// Marsaglia (1972): a uniform point on the unit sphere from a uniform point of the unit disc.
Vec3 unit_sphere(RandomStream& rng);

// Cosine-weighted direction about the unit normal n: n plus a uniform unit vector, normalised,
// is distributed as cos θ / π over the hemisphere (the point n + s lies on the unit sphere
// tangent to the surface, whose projection gives Lambert's law).
Vec3 cosine_direction(const Vec3& n, RandomStream& rng);

// Mirror reflection of the direction d about the unit normal n: d - 2 (d·n) n.
inline Vec3 specular_reflection(const Vec3& d, const Vec3& n) {
  const double twice = 2 * dot(d, n);
  return {d[0] - twice * n[0], d[1] - twice * n[1], d[2] - twice * n[2]};
}

// Distance along the unit direction d from o to the sphere (c, r): 0 when o is inside it, +inf
// on a miss.
inline double sphere_hit_distance(const Vec3& o, const Vec3& d, const Vec3& c, double r) {
  const Vec3 oc = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
  const double cc = dot(oc, oc) - r * r;
  if (cc < 0) return 0;
  const double b = dot(oc, d);
  if (b >= 0) return std::numeric_limits<double>::infinity();  // outside and moving away
  const double disc = b * b - cc;
  if (disc < 0) return std::numeric_limits<double>::infinity();
  return cc / (-b + std::sqrt(disc));  // = -b - √disc without the cancellation
}

class SphereGrid {
 public:
  static constexpr std::uint32_t kNoSphere = std::numeric_limits<std::uint32_t>::max() - 2;

  // The bed is kept by reference: it must outlive the grid. An empty bed gives a grid that
  // every ray misses.
  explicit SphereGrid(const Bed& bed);

  // Nearest sphere (other than `skip`) hit by o + t d, d a unit vector, with t < t_limit:
  // {sphere, t}, or {kNoSphere, t_limit}. A ray that starts outside the grid's box is first
  // advanced to where it enters it.
  std::pair<std::uint32_t, double> first_hit(const Vec3& o, const Vec3& d, std::uint32_t skip,
                                             double t_limit) const;

  Vec3 centre(std::uint32_t s) const { return {bed_.x[s], bed_.y[s], bed_.z[s]}; }
  double radius(std::uint32_t s) const { return bed_.radius[s]; }

 private:
  std::size_t cells() const;
  int index(int k, double v) const;
  std::size_t flat(int a, int b, int e) const;
  // Entry distance of o + t d into the grid's box, +inf when the ray misses it.
  double entry(const Vec3& o, const Vec3& d) const;

  const Bed& bed_;
  double origin_[3] = {0, 0, 0}, span_[3] = {0, 0, 0}, cell_ = 1;
  int dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> start_, items_;
};

}  // namespace powderbed::bed
