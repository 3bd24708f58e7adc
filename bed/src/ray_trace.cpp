#include "powderbed/bed/ray_trace.hpp"

#include <algorithm>

namespace powderbed::bed {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

Vec3 unit_sphere(RandomStream& rng) {
  for (;;) {
    const double u = 2 * rng.uniform() - 1, v = 2 * rng.uniform() - 1, s = u * u + v * v;
    if (s >= 1) continue;
    const double w = 2 * std::sqrt(1 - s);
    return {u * w, v * w, 1 - 2 * s};
  }
}

Vec3 cosine_direction(const Vec3& n, RandomStream& rng) {
  for (;;) {
    const Vec3 s = unit_sphere(rng);
    const Vec3 d = {n[0] + s[0], n[1] + s[1], n[2] + s[2]};
    const double len = std::sqrt(dot(d, d));
    if (len > 1e-9) return {d[0] / len, d[1] / len, d[2] / len};
  }
}

SphereGrid::SphereGrid(const Bed& bed) : bed_(bed) {
  const std::size_t n = bed.n();
  if (n == 0) {
    start_.assign(2, 0);
    return;
  }
  const double r_max = *std::max_element(bed.radius.begin(), bed.radius.end());
  double size = 2 * r_max;
  for (int k = 0; k < 3; ++k) {
    origin_[k] = bed.domain.lower[static_cast<std::size_t>(k)] - r_max;
    span_[k] = bed.domain.length(k) + 2 * r_max;
  }
  // Coarsen a sparse bed so the grid holds at most ~8 cells per particle.
  while (span_[0] / size * span_[1] / size * span_[2] / size > 8.0 * static_cast<double>(n) + 64)
    size *= 1.5;
  cell_ = size;
  for (int k = 0; k < 3; ++k) dims_[k] = std::max(1, static_cast<int>(std::ceil(span_[k] / cell_)));
  std::vector<std::uint32_t> count(cells() + 1, 0);
  const auto visit = [&](std::size_t p, auto&& f) {
    const Vec3 c = {bed.x[p], bed.y[p], bed.z[p]};
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

double SphereGrid::entry(const Vec3& o, const Vec3& d) const {
  double t_in = 0, t_out = kInf;
  for (std::size_t k = 0; k < 3; ++k) {
    const double lo = origin_[k], hi = origin_[k] + span_[k];
    if (d[k] == 0) {
      if (o[k] < lo || o[k] > hi) return kInf;
      continue;
    }
    double t0 = (lo - o[k]) / d[k], t1 = (hi - o[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    t_in = std::max(t_in, t0);
    t_out = std::min(t_out, t1);
  }
  return t_in <= t_out ? t_in : kInf;
}

std::pair<std::uint32_t, double> SphereGrid::first_hit(const Vec3& o_in, const Vec3& d,
                                                       std::uint32_t skip, double t_limit) const {
  if (items_.empty()) return {kNoSphere, t_limit};
  const double t0 = entry(o_in, d);
  if (!(t0 < t_limit)) return {kNoSphere, t_limit};
  // Distances below are measured from the entry point; the answer adds t0 back.
  const Vec3 o = {o_in[0] + t0 * d[0], o_in[1] + t0 * d[1], o_in[2] + t0 * d[2]};
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
  std::uint32_t best = kNoSphere;
  double best_t = t_limit - t0;
  for (;;) {
    const std::size_t cell = flat(c[0], c[1], c[2]);
    for (std::uint32_t q = start_[cell]; q < start_[cell + 1]; ++q) {
      const std::uint32_t s = items_[q];
      if (s == skip) continue;
      const double t = sphere_hit_distance(o, d, centre(s), bed_.radius[s]);
      if (t < best_t) best_t = t, best = s;
    }
    const int k = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2)
                                        : (t_next[1] < t_next[2] ? 1 : 2);
    if (best_t <= t_next[k]) break;  // nothing in a later cell can be nearer
    c[k] += step[k];
    if (c[k] < 0 || c[k] >= dims_[k]) break;
    t_next[k] += t_delta[k];
  }
  return {best, best == kNoSphere ? t_limit : best_t + t0};
}

std::size_t SphereGrid::cells() const {
  return static_cast<std::size_t>(dims_[0]) * static_cast<std::size_t>(dims_[1]) *
         static_cast<std::size_t>(dims_[2]);
}

int SphereGrid::index(int k, double v) const {
  return std::clamp(static_cast<int>(std::floor((v - origin_[k]) / cell_)), 0, dims_[k] - 1);
}

std::size_t SphereGrid::flat(int a, int b, int e) const {
  return (static_cast<std::size_t>(e) * static_cast<std::size_t>(dims_[1]) +
          static_cast<std::size_t>(b)) * static_cast<std::size_t>(dims_[0]) +
         static_cast<std::size_t>(a);
}

}  // namespace powderbed::bed
