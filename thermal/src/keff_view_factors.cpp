#include "powderbed/thermal/keff_view_factors.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>

#include "powderbed/bed/errors.hpp"

namespace powderbed::thermal {
namespace {

using Vec = std::array<double, 3>;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max() - 2;

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// SplitMix64 (Steele, Lea & Flood 2014): a small generator whose output is the same on every
// platform (std:: distributions are not), seeded per particle so threads do not matter.
class Stream {
 public:
  Stream(std::uint64_t seed, std::uint64_t particle)
      : state_(seed * 0x9E3779B97F4A7C15ULL ^ (particle + 1) * 0xD1B54A32D192ED03ULL) {
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
Vec unit_sphere(Stream& rng) {
  for (;;) {
    const double u = 2 * rng.uniform() - 1, v = 2 * rng.uniform() - 1, s = u * u + v * v;
    if (s >= 1) continue;
    const double w = 2 * std::sqrt(1 - s);
    return {u * w, v * w, 1 - 2 * s};
  }
}

// Cosine-weighted direction about the unit normal n: n plus a uniform unit vector, normalised,
// is distributed as cos θ / π over the hemisphere (the point n + s lies on the unit sphere
// tangent to the surface, whose projection gives Lambert's law).
Vec cosine_direction(const Vec& n, Stream& rng) {
  for (;;) {
    const Vec s = unit_sphere(rng);
    const Vec d = {n[0] + s[0], n[1] + s[1], n[2] + s[2]};
    const double len = std::sqrt(dot(d, d));
    if (len > 1e-9) return {d[0] / len, d[1] / len, d[2] / len};
  }
}

// Uniform grid over the domain grown by r_max; each cell lists every sphere that may overlap it
// (its bounding box does).
class Grid {
 public:
  Grid(const bed::Bed& bed, double r_max) : bed_(bed) {
    const std::size_t n = bed.n();
    double size = 2 * r_max;
    for (int k = 0; k < 3; ++k) {
      origin_[k] = bed.domain.lower[static_cast<std::size_t>(k)] - r_max;
      span_[k] = bed.domain.length(k) + 2 * r_max;
    }
    // Coarsen a sparse bed so the grid holds at most ~8 cells per particle.
    while (span_[0] / size * span_[1] / size * span_[2] / size > 8.0 * static_cast<double>(n) + 64)
      size *= 1.5;
    cell_ = size;
    for (int k = 0; k < 3; ++k)
      dims_[k] = std::max(1, static_cast<int>(std::ceil(span_[k] / cell_)));
    std::vector<std::uint32_t> count(cells() + 1, 0);
    const auto visit = [&](std::size_t p, auto&& f) {
      const Vec c = {bed.x[p], bed.y[p], bed.z[p]};
      int lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {
        lo[k] = index(k, c[static_cast<std::size_t>(k)] - bed.radius[p]);
        hi[k] = index(k, c[static_cast<std::size_t>(k)] + bed.radius[p]);
      }
      for (int a = lo[0]; a <= hi[0]; ++a)
        for (int b = lo[1]; b <= hi[1]; ++b)
          for (int e = lo[2]; e <= hi[2]; ++e) f(flat(a, b, e));
    };
    for (std::size_t p = 0; p < n; ++p) visit(p, [&](std::size_t c) { ++count[c + 1]; });
    for (std::size_t c = 0; c < cells(); ++c) count[c + 1] += count[c];
    start_ = count;
    items_.resize(start_.back());
    for (std::size_t p = 0; p < n; ++p)
      visit(p, [&](std::size_t c) { items_[count[c]++] = static_cast<std::uint32_t>(p); });
  }

  // Nearest sphere (other than `skip`) hit by o + t d with t < t_limit: {sphere, t}, or kNone.
  std::pair<std::uint32_t, double> first_hit(const Vec& o, const Vec& d, std::uint32_t skip,
                                             double t_limit) const {
    int c[3], step[3];
    double t_next[3], t_delta[3];
    for (int k = 0; k < 3; ++k) {
      const auto K = static_cast<std::size_t>(k);
      c[k] = index(k, o[K]);
      const double lo = origin_[k] + c[k] * cell_;
      if (d[K] > 0) {
        step[k] = 1, t_next[k] = (lo + cell_ - o[K]) / d[K], t_delta[k] = cell_ / d[K];
      } else if (d[K] < 0) {
        step[k] = -1, t_next[k] = (lo - o[K]) / d[K], t_delta[k] = -cell_ / d[K];
      } else {
        step[k] = 0, t_next[k] = kInf, t_delta[k] = kInf;
      }
    }
    std::uint32_t best = kNone;
    double best_t = t_limit;
    for (;;) {
      const std::size_t cell = flat(c[0], c[1], c[2]);
      for (std::uint32_t q = start_[cell]; q < start_[cell + 1]; ++q) {
        const std::uint32_t s = items_[q];
        if (s == skip) continue;
        const double t = sphere_hit(o, d, s);
        if (t < best_t) best_t = t, best = s;
      }
      const int k = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2)
                                          : (t_next[1] < t_next[2] ? 1 : 2);
      if (best_t <= t_next[k]) break;  // nothing in a later cell can be nearer
      c[k] += step[k];
      if (c[k] < 0 || c[k] >= dims_[k]) break;
      t_next[k] += t_delta[k];
    }
    return {best, best_t};
  }

 private:
  std::size_t cells() const {
    return static_cast<std::size_t>(dims_[0]) * static_cast<std::size_t>(dims_[1]) *
           static_cast<std::size_t>(dims_[2]);
  }
  int index(int k, double v) const {
    return std::clamp(static_cast<int>(std::floor((v - origin_[k]) / cell_)), 0, dims_[k] - 1);
  }
  std::size_t flat(int a, int b, int e) const {
    return (static_cast<std::size_t>(e) * static_cast<std::size_t>(dims_[1]) +
            static_cast<std::size_t>(b)) * static_cast<std::size_t>(dims_[0]) +
           static_cast<std::size_t>(a);
  }
  // Distance along the unit direction d to sphere s: 0 when o is inside it, kInf on a miss.
  double sphere_hit(const Vec& o, const Vec& d, std::uint32_t s) const {
    const Vec oc = {o[0] - bed_.x[s], o[1] - bed_.y[s], o[2] - bed_.z[s]};
    const double r = bed_.radius[s];
    const double c = dot(oc, oc) - r * r;
    if (c < 0) return 0;
    const double b = dot(oc, d);
    if (b >= 0) return kInf;  // outside and moving away
    const double disc = b * b - c;
    if (disc < 0) return kInf;
    return c / (-b + std::sqrt(disc));  // = -b - √disc without the cancellation
  }

  const bed::Bed& bed_;
  double origin_[3], span_[3], cell_;
  int dims_[3];
  std::vector<std::uint32_t> start_, items_;
};

// First thing a ray from particle p's surface point o in direction d hits: a sphere, a wall,
// or kNone after kMaxReflections in the side mirrors.
std::uint32_t trace(const bed::Bed& bed, const Grid& grid, int axis, std::uint32_t p, Vec o,
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
std::size_t wall_rays(const bed::Bed& bed, const Grid& grid, const ViewFactorParams& params,
                      double& wall_to_wall) {
  const auto a = static_cast<std::size_t>(params.axis);
  const std::size_t u = (a + 1) % 3, v = (a + 2) % 3;
  double mean_radius = 0;
  for (const double r : bed.radius) mean_radius += r / static_cast<double>(bed.n());
  const double wall_area = bed.domain.length(static_cast<int>(u)) *
                           bed.domain.length(static_cast<int>(v));
  const double spheres = std::ceil(wall_area / (4 * std::numbers::pi * mean_radius * mean_radius));
  const auto per_wall = static_cast<std::size_t>(
      std::min(static_cast<double>(params.rays) * spheres, kMaxWallRays));
  std::size_t lost = 0, crossed = 0;
  for (const bool hot : {true, false}) {
    Stream rng(params.seed, bed.n() + (hot ? 0 : 1));
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
    throw InputError("radiation.rays: 0 is out of range (accepted: at least 1 ray per particle)");
  ViewFactors vf;
  vf.rays = params.rays;
  const std::size_t n = bed.n();
  if (n == 0) return vf;
  const Grid grid(bed, *std::max_element(bed.radius.begin(), bed.radius.end()));
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
      Stream rng(params.seed, p);
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

}  // namespace powderbed::thermal
