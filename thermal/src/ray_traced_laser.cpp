#include "powderbed/thermal/ray_traced_laser.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/ray_trace.hpp"
#include "powderbed/thermal/fresnel_absorptance.hpp"
#include "powderbed/thermal/rough_reflection.hpp"

namespace powderbed::thermal {

namespace {

using bed::Vec3;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Rays of one trace are summed in this many chunks, in chunk order (thread-count independent).
constexpr std::size_t kChunks = 64;

struct Event {
  std::uint32_t target;
  double power;  // fraction of the beam
};

struct ChunkTally {
  std::vector<Event> particles, nodes;
  double escaped = 0, outside = 0, dropped = 0, hits = 0, depression = 0;
};

// The substrate's surface under one trace: per column the solid's top (the plate's top face
// raised by the part, TraceSurfaces::rise) less its depression (TraceSurfaces::depression),
// bilinear between the columns' nodes. The tracer's reference plane is the highest point of that
// surface, `top()`: a ray meets it from above as a flat face or enters the space under it,
// marched through to the surface (the depression's cavity, or the lower solid beside a raised
// one). `over` bounds the columns below the plane (none: flat at top()).
class Surface {
 public:
  Surface(const SubstrateGeometry& g, const TraceSurfaces& f) : g_(g), cavity_(f.depression) {
    std::vector<double> height(g.columns(), g.z_top);
    for (std::size_t c = 0; c < height.size(); ++c) {
      if (!f.rise.empty()) height[c] += f.rise[c];
      if (!f.depression.empty()) height[c] -= f.depression[c];
    }
    top_ = *std::max_element(height.begin(), height.end());
    depth_.resize(height.size());
    for (std::size_t c = 0; c < height.size(); ++c) {
      depth_[c] = top_ - height[c];
      if (depth_[c] <= 0) continue;
      const double x = g.x(c % g.nx), y = g.y(c / g.nx);
      lo_ = {std::min(lo_[0], x - g.dx), std::min(lo_[1], y - g.dy)};
      hi_ = {std::max(hi_[0], x + g.dx), std::max(hi_[1], y + g.dy)};
    }
  }
  double top() const { return top_; }
  // Whether the surface at (x, y) may lie below top().
  bool over(double x, double y) const {
    return x > lo_[0] && x < hi_[0] && y > lo_[1] && y < hi_[1];
  }
  // How far the surface at (x, y) lies below top(); the gradient of that depth.
  double depth(double x, double y, double* ddx = nullptr, double* ddy = nullptr) const {
    return bilinear(depth_, x, y, ddx, ddy);
  }
  // Whether (x, y) lies in the vapour depression (its wall is molten), not on the solid's top.
  bool in_depression(double x, double y) const {
    return !cavity_.empty() && bilinear(cavity_, x, y) > 0;
  }
  // Below the surface: the point lies inside the solid or melt.
  bool inside(const Vec3& p) const { return p[2] < top_ - depth(p[0], p[1]); }

 private:
  double bilinear(const std::vector<double>& f, double x, double y, double* ddx = nullptr,
                  double* ddy = nullptr) const {
    const double fx = std::clamp((x - g_.x0) / g_.dx, 0.0, static_cast<double>(g_.nx - 1) - 1e-9);
    const double fy = std::clamp((y - g_.y0) / g_.dy, 0.0, static_cast<double>(g_.ny - 1) - 1e-9);
    const auto i = static_cast<std::size_t>(fx), j = static_cast<std::size_t>(fy);
    const double u = fx - static_cast<double>(i), v = fy - static_cast<double>(j);
    const double* d = f.data() + i + g_.nx * j;
    const double d00 = d[0], d10 = d[1], d01 = d[g_.nx], d11 = d[g_.nx + 1];
    if (ddx) *ddx = ((1 - v) * (d10 - d00) + v * (d11 - d01)) / g_.dx;
    if (ddy) *ddy = ((1 - u) * (d01 - d00) + u * (d11 - d10)) / g_.dy;
    return (1 - v) * ((1 - u) * d00 + u * d10) + v * ((1 - u) * d01 + u * d11);
  }
  const SubstrateGeometry& g_;
  const std::vector<double>& cavity_;
  std::vector<double> depth_;
  double top_ = 0;
  std::array<double, 2> lo_{kInf, kInf}, hi_{-kInf, -kInf};
};

// Where a ray under the surface's top plane next meets the surface: marching along it from `o`
// in steps `h`, then bisecting the step that crossed it. nullopt: the ray rose back through the
// top plane first (at parameter `*t_exit`).
std::optional<double> cavity_hit(const Surface& surface, const Vec3& o, const Vec3& d, double h,
                                 double* t_exit) {
  const auto at = [&](double t) { return Vec3{o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]}; };
  double t0 = 0;
  for (;;) {
    const double t1 = t0 + h;
    const Vec3 p = at(t1);
    if (p[2] >= surface.top() && d[2] > 0) {
      *t_exit = (surface.top() - o[2]) / d[2];
      return std::nullopt;
    }
    if (surface.inside(p)) {
      double a = t0, b = t1;
      for (int k = 0; k < 30; ++k) {
        const double m = 0.5 * (a + b);
        (surface.inside(at(m)) ? b : a) = m;
      }
      return a;
    }
    t0 = t1;
  }
}

}  // namespace

double SurfaceOptics::absorptance(unsigned liquid, double cos_incidence) const {
  if (model == Optics::constant) return alpha[liquid];
  return fresnel_absorptance(index[liquid], cos_incidence);
}

struct BeamTracer::Impl {
  bed::Bed bed;
  std::vector<std::uint32_t> index;  // position in `bed` -> caller's particle index
  std::unique_ptr<bed::SphereGrid> grid;
  SubstrateGeometry g;
  double spot_radius = 0, z_start = 0;
  RayTraceParams params;
  SurfaceOptics optics;

  void rebuild() {
    grid = std::make_unique<bed::SphereGrid>(bed);
    double top = g.z_top;
    for (std::size_t i = 0; i < bed.n(); ++i) top = std::max(top, bed.z[i] + bed.radius[i]);
    z_start = top + 1e-6 * std::max(spot_radius, top - g.z_top);  // just above the highest top
  }

  // Follows one ray of power `power` from o downwards; books what it leaves where.
  void follow(Vec3 o, double power, const TraceSurfaces& surfaces, const Surface& surface,
              bed::RandomStream& rng, ChunkTally& tally) const;
  // Books `absorbed` at the top face or wall point p on the columns around it.
  void book_top(const Vec3& p, double absorbed, ChunkTally& tally) const {
    const TopStencil st = top_stencil(g, p[0], p[1]);
    for (int w = 0; w < 4; ++w)
      if (st.weight[w] > 0)
        tally.nodes.push_back({static_cast<std::uint32_t>(st.column[w]), st.weight[w] * absorbed});
  }
  // Share of the reflected light that goes on specularly from a hit on a surface of phase
  // `liquid`; `top_face`: the substrate's flat top, not a particle or the depression's wall.
  double specular(bool top_face, unsigned liquid, double cos_incidence) const {
    switch (params.reflection) {
      case Reflection::specular: return 1;
      case Reflection::diffuse: return 0;
      case Reflection::rough:
        return top_face && !liquid
                   ? specular_share(params.roughness, params.wavelength, cos_incidence)
                   : 1;
    }
    return 1;
  }
  unsigned column_phase(const Vec3& p, const TraceSurfaces& surfaces) const {
    const TopStencil st = top_stencil(g, p[0], p[1]);
    const int nearest = static_cast<int>(std::max_element(st.weight, st.weight + 4) - st.weight);
    return surfaces.node_phase[st.column[nearest]];
  }
};

void BeamTracer::Impl::follow(Vec3 o, double power, const TraceSurfaces& surfaces,
                              const Surface& surface, bed::RandomStream& rng,
                              ChunkTally& tally) const {
  const double floor_power = params.cutoff * power;
  const double x1 = g.x(g.nx - 1), y1 = g.y(g.ny - 1);
  const double march = 0.5 * std::min(g.dx, g.dy);
  const auto off_grid = [&](const Vec3& p) { return p[0] < g.x0 || p[0] > x1 || p[1] < g.y0 || p[1] > y1; };
  Vec3 d = {0, 0, -1};
  std::uint32_t skip = bed::SphereGrid::kNoSphere;
  bool below = false;  // under the surface's top plane: in a depression or beside a raised top
  for (int bounce = 0; bounce < params.max_bounces; ++bounce) {
    // The surface ahead: under the plane by marching to it (or back up through the plane), from
    // above by meeting the plane; a sphere nearer than either is hit first.
    double reach = kInf;
    bool wall = false;  // the surface ahead lies under the plane
    if (below) {
      double t_exit = 0;
      const auto t = cavity_hit(surface, o, d, march, &t_exit);
      reach = t ? *t : t_exit;
      wall = t.has_value();
    } else if (d[2] < 0) {
      reach = (surface.top() - o[2]) / d[2];
    }
    const auto [s, t] = grid->first_hit(o, d, skip, reach);
    if (s == bed::SphereGrid::kNoSphere && !std::isfinite(reach)) {
      tally.escaped += power;
      return;
    }
    const double along = s == bed::SphereGrid::kNoSphere ? reach : t;
    const Vec3 p = {o[0] + along * d[0], o[1] + along * d[1], o[2] + along * d[2]};
    Vec3 n;
    double alpha, mirror;  // absorbed fraction; specular share of the rest
    if (s != bed::SphereGrid::kNoSphere) {
      tally.hits += 1;
      const Vec3 c = grid->centre(s);
      n = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
      const double len = std::sqrt(bed::dot(n, n));
      for (double& v : n) v /= len;  // normalised: a ray that starts inside a sphere hits at o
      const std::uint32_t target = index[s];
      alpha = optics.absorptance(surfaces.particle_phase[target], -bed::dot(d, n));
      mirror = specular(false, surfaces.particle_phase[target], -bed::dot(d, n));
      tally.particles.push_back({target, alpha * power});
      skip = s;
    } else {
      skip = bed::SphereGrid::kNoSphere;
      if (below && !wall) {  // back up through the plane: on among the spheres above it
        o = {p[0], p[1], surface.top()};
        below = false;
        continue;
      }
      const bool into = !below && surface.over(p[0], p[1]) && surface.depth(p[0], p[1]) > 0;
      if (!into) tally.hits += 1;
      if (off_grid(p)) {
        tally.outside += power;
        return;
      }
      if (into) {  // into the space under the plane
        o = p;
        below = true;
        continue;
      }
      n = {0, 0, 1};
      if (wall) {
        double ddx = 0, ddy = 0;
        surface.depth(p[0], p[1], &ddx, &ddy);
        n = {ddx, ddy, 1};
        const double len = std::sqrt(bed::dot(n, n));
        for (double& v : n) v /= len;
      }
      const bool molten_wall = wall && surface.in_depression(p[0], p[1]);  // the depression's
      const unsigned phase = molten_wall ? 1 : column_phase(p, surfaces);
      alpha = optics.absorptance(phase, -bed::dot(d, n));
      mirror = specular(!molten_wall, phase, -bed::dot(d, n));
      book_top(p, alpha * power, tally);
      if (molten_wall) tally.depression += alpha * power;
    }
    power *= 1 - alpha;
    if (power < floor_power) {
      tally.dropped += power;
      return;
    }
    // A mixed surface draws which way this ray goes (the stream is the trace's own: the same
    // for any thread count); a pure one draws nothing.
    const bool specular_ray = mirror >= 1 || (mirror > 0 && rng.uniform() < mirror);
    d = specular_ray ? bed::specular_reflection(d, n) : bed::cosine_direction(n, rng);
    o = p;
  }
  tally.dropped += power;
}

void validate(const RayTraceParams& params) {
  if (params.rays == 0)
    throw InputError("laser.rays: 0 (accepted: at least 1 ray per traced beam position)");
  if (!(params.cutoff > 0 && params.cutoff < 1))
    throw InputError("laser.ray-cutoff: " + std::to_string(params.cutoff) +
                     " (accepted: 0 < cutoff < 1, the fraction of its power below which a ray "
                     "is dropped)");
  if (!(params.roughness >= 0 && std::isfinite(params.roughness)))
    throw InputError("laser.roughness: " + std::to_string(params.roughness) +
                     " (accepted: a finite rms height >= 0, m)");
  if (!(params.wavelength > 0 && std::isfinite(params.wavelength)))
    throw InputError("laser.wavelength: " + std::to_string(params.wavelength) +
                     " (accepted: a finite wavelength > 0, m)");
}

BeamTracer::BeamTracer(const bed::Bed& bed, const SubstrateGeometry& g, double spot_radius,
                       const RayTraceParams& params, const SurfaceOptics& optics)
    : impl_(std::make_unique<Impl>()) {
  validate(params);
  Impl& m = *impl_;
  m.optics = optics;
  m.bed = bed;
  m.g = g;
  m.spot_radius = spot_radius;
  m.params = params;
  m.index.resize(bed.n());
  for (std::size_t i = 0; i < bed.n(); ++i) m.index[i] = static_cast<std::uint32_t>(i);
  m.rebuild();
}

BeamTracer::~BeamTracer() = default;

void BeamTracer::update(const std::vector<std::uint8_t>& gone, const std::vector<double>& z,
                        const std::vector<double>& radius) {
  Impl& m = *impl_;
  bed::Bed kept;
  kept.domain = m.bed.domain;
  std::vector<std::uint32_t> index;
  for (std::size_t i = 0; i < m.bed.n(); ++i) {
    const std::uint32_t p = m.index[i];
    if (gone[p]) continue;
    kept.x.push_back(m.bed.x[i]);
    kept.y.push_back(m.bed.y[i]);
    kept.z.push_back(z[p]);
    kept.radius.push_back(radius[p]);
    kept.id.push_back(m.bed.id[i]);
    index.push_back(p);
  }
  m.bed = std::move(kept);
  m.index = std::move(index);
  m.rebuild();
}

AbsorptionMap BeamTracer::trace(double x, double y, std::uint64_t trace,
                                const TraceSurfaces& surfaces) const {
  const Impl& m = *impl_;
  const Surface surface(m.g, surfaces);
  // Rays start above the highest particle and the highest point of the surface.
  const double z_start = std::max(m.z_start, surface.top() + 1e-6 * m.spot_radius);
  const std::size_t rays = m.params.rays;
  bed::RandomStream jitter(m.params.seed, trace);
  const double xi = jitter.uniform(), zeta = jitter.uniform();
  const double golden = 0.5 * (std::sqrt(5.0) - 1);
  const double per_ray = 1.0 / static_cast<double>(rays);
  const std::size_t chunks = std::min(kChunks, rays);
  std::vector<ChunkTally> tally(chunks);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    bed::RandomStream rng(m.params.seed ^ 0x5DEECE66DULL, trace * kChunks + c);
    for (std::size_t k = c * rays / chunks; k < (c + 1) * rays / chunks; ++k) {
      const double u = (static_cast<double>(k) + xi) * per_ray;
      const double v = std::fmod(static_cast<double>(k) * golden + zeta, 1.0);
      const double r = m.spot_radius * std::sqrt(-0.5 * std::log1p(-u));
      const double phi = 2 * std::numbers::pi * v;
      m.follow({x + r * std::cos(phi), y + r * std::sin(phi), z_start}, per_ray, surfaces, surface,
               rng, tally[c]);
    }
  }
  // Chunk order, then target order: the same sums for any thread count.
  AbsorptionMap map;
  std::vector<double> particles(surfaces.particle_phase.size(), 0.0), nodes;
  std::vector<std::uint32_t> node_targets;
  for (const ChunkTally& t : tally) {
    for (const Event& e : t.particles) particles[e.target] += e.power;
    for (const Event& e : t.nodes) node_targets.push_back(e.target);
    map.escaped += t.escaped;
    map.outside += t.outside;
    map.dropped += t.dropped;
    map.hits += t.hits * per_ray;
    map.absorbed_depression += t.depression;
  }
  std::sort(node_targets.begin(), node_targets.end());
  node_targets.erase(std::unique(node_targets.begin(), node_targets.end()), node_targets.end());
  nodes.assign(node_targets.size(), 0.0);
  for (const ChunkTally& t : tally)
    for (const Event& e : t.nodes)
      nodes[static_cast<std::size_t>(
          std::lower_bound(node_targets.begin(), node_targets.end(), e.target) -
          node_targets.begin())] += e.power;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles[i] <= 0) continue;
    map.particles.push_back({static_cast<std::uint32_t>(i), particles[i]});
    map.absorbed_particles += particles[i];
  }
  for (std::size_t q = 0; q < nodes.size(); ++q) {
    map.nodes.push_back({node_targets[q], nodes[q]});
    map.absorbed_substrate += nodes[q];
  }
  return map;
}

}  // namespace powderbed::thermal
