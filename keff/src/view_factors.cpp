#include "powderbed/keff/view_factors.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/ray_trace.hpp"

namespace powderbed::keff {
namespace {

using bed::cosine_direction;
using bed::RandomStream;
using bed::SphereGrid;
using bed::unit_sphere;
using Vec = bed::Vec3;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNone = SphereGrid::kNoSphere;

// First thing a ray from particle p's surface point o in direction d hits: a sphere, a wall,
// or kNone after kMaxReflections in the side mirrors.
std::uint32_t trace(const bed::Bed& bed, const SphereGrid& grid, int axis, std::uint32_t p, Vec o,
                    Vec d) {
  std::uint32_t skip = p;  // a convex sphere cannot see itself, except in a mirror
  for (int bounce = 0; bounce <= kMaxReflections; ++bounce) {
    // The first face the ray crosses (0 when o is already beyond it).
    int face = 0;
    double t_face = kInf;
    for (int k = 0; k < 3; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (d[K] == 0) continue;
      const double plane = d[K] > 0 ? bed.domain.upper[K] : bed.domain.lower[K];
      const double t = std::max(0.0, (plane - o[K]) / d[K]);
      if (t < t_face) t_face = t, face = k;
    }
    const auto [s, t] = grid.first_hit(o, d, skip, t_face);
    if (s != kNone) return s;
    const auto F = static_cast<std::size_t>(face);
    if (face == axis) return d[F] > 0 ? kHotWall : kColdWall;
    for (std::size_t k = 0; k < 3; ++k) o[k] += t_face * d[k];
    d[F] = -d[F];
    skip = kNone;
  }
  return kNone;
}

// F between the walls (see the header); returns the rays lost in the mirrors. Each wall draws
// from the streams of particle indices n and n + 1, after the particles'.
std::size_t wall_rays(const bed::Bed& bed, const SphereGrid& grid, const ViewFactorParams& params,
                      double& wall_to_wall) {
  const auto a = static_cast<std::size_t>(params.axis);
  const std::size_t u = (a + 1) % 3, v = (a + 2) % 3;
  double mean_radius = 0;
  for (const double r : bed.radius) mean_radius += r / static_cast<double>(bed.n());
  const double wall_area = bed.domain.length(static_cast<int>(u)) *
                           bed.domain.length(static_cast<int>(v));
  const double spheres = std::ceil(wall_area / bed::sphere_area(mean_radius));
  const auto per_wall = static_cast<std::size_t>(
      std::min(static_cast<double>(params.rays) * spheres, kMaxWallRays));
  std::size_t lost = 0, crossed = 0;
  for (const bool hot : {true, false}) {
    RandomStream rng(params.seed, bed.n() + (hot ? 0 : 1));
    Vec normal = {0, 0, 0};
    normal[a] = hot ? -1 : 1;  // into the box
    const std::uint32_t other = hot ? kColdWall : kHotWall;
    for (std::size_t ray = 0; ray < per_wall; ++ray) {
      Vec o;
      o[a] = hot ? bed.domain.upper[a] : bed.domain.lower[a];
      o[u] = bed.domain.lower[u] + rng.uniform() * bed.domain.length(static_cast<int>(u));
      o[v] = bed.domain.lower[v] + rng.uniform() * bed.domain.length(static_cast<int>(v));
      const std::uint32_t j = trace(bed, grid, params.axis, kNone, o, cosine_direction(normal, rng));
      lost += j == kNone;
      crossed += j == other;
    }
  }
  wall_to_wall = static_cast<double>(crossed) / static_cast<double>(2 * per_wall);
  return lost;
}

}  // namespace

ViewFactors view_factors(const bed::Bed& bed, const ViewFactorParams& params) {
  if (bed.domain.dimension != 3)
    throw InputError("bed: a 2D bed (accepted: a 3D bed of spheres)");
  if (params.rays == 0)
    throw InputError("rays: 0 is out of range (accepted: at least 1 ray per particle)");
  ViewFactors vf;
  vf.rays = params.rays;
  const std::size_t n = bed.n();
  if (n == 0) return vf;
  const SphereGrid grid(bed);
  std::vector<std::vector<ViewFactorEntry>> rows(n);
  std::size_t lost = 0;
  const double per_ray = 1.0 / static_cast<double>(params.rays);
  std::atomic<std::size_t> traced{0};
  const std::size_t report_every = std::max<std::size_t>(1, n / 100);  // about every 1 %

#pragma omp parallel reduction(+ : lost)
  {
    const bool reporter = params.progress && omp_get_thread_num() == 0;
    std::size_t next_report = report_every;
    // Hit counts of the current particle: particles, then the two walls.
    std::vector<std::uint32_t> hits(n + 2, 0);
    std::vector<std::uint32_t> touched;
#pragma omp for schedule(dynamic, 16)
    for (std::size_t p = 0; p < n; ++p) {
      RandomStream rng(params.seed, p);
      const auto i = static_cast<std::uint32_t>(p);
      const Vec c = {bed.x[p], bed.y[p], bed.z[p]};
      for (std::size_t ray = 0; ray < params.rays; ++ray) {
        const Vec normal = unit_sphere(rng);
        const Vec o = {c[0] + bed.radius[p] * normal[0], c[1] + bed.radius[p] * normal[1],
                       c[2] + bed.radius[p] * normal[2]};
        const std::uint32_t j = trace(bed, grid, params.axis, i, o, cosine_direction(normal, rng));
        if (j == kNone) {
          ++lost;
          continue;
        }
        const std::size_t slot = j == kHotWall ? n : j == kColdWall ? n + 1 : j;
        if (hits[slot]++ == 0) touched.push_back(static_cast<std::uint32_t>(slot));
      }
      std::sort(touched.begin(), touched.end());
      std::vector<ViewFactorEntry>& row = rows[p];
      row.reserve(touched.size());
      // Slots n, n + 1 sort last; kColdWall < kHotWall keeps the row sorted by j.
      for (const std::uint32_t slot : touched) {
        if (slot < n) row.push_back({i, slot, hits[slot] * per_ray});
      }
      if (hits[n + 1]) row.push_back({i, kColdWall, hits[n + 1] * per_ray});
      if (hits[n]) row.push_back({i, kHotWall, hits[n] * per_ray});
      for (const std::uint32_t slot : touched) hits[slot] = 0;
      touched.clear();
      const std::size_t done = traced.fetch_add(1, std::memory_order_relaxed) + 1;
      if (reporter && done >= next_report) {
        params.progress(static_cast<double>(done) / static_cast<double>(n));
        next_report = done + report_every;
      }
    }
  }
  if (params.progress) params.progress(1.0);

  vf.lost_rays = lost + wall_rays(bed, grid, params, vf.wall_to_wall);
  std::size_t total = 0;
  for (const auto& row : rows) total += row.size();
  vf.entries.reserve(total);
  for (const auto& row : rows) vf.entries.insert(vf.entries.end(), row.begin(), row.end());
  return vf;
}

}  // namespace powderbed::keff
