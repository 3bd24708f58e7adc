#include "powderbed/dem/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "box.hpp"
#include "neighbour_list.hpp"
#include "powderbed/dem/hertz_normal.hpp"

namespace powderbed::dem {

namespace {

using detail::Box;

double mass_of(double radius, double density) {
  return 4.0 / 3.0 * std::numbers::pi * radius * radius * radius * density;
}

// Calls f(i, j, delta, r_star) once per overlapping pair (i < j).
template <class F>
void for_each_overlap(const bed::Bed& bed, F&& f) {
  if (bed.n() == 0) return;
  const Box box = Box::from(bed.domain);
  const double r_max = *std::max_element(bed.radius.begin(), bed.radius.end());
  detail::NeighbourList list;
  // The diagnostic may see a box too small for a periodic cell list; treat it as closed then.
  Box search = box;
  for (int a = 0; a < 3; ++a) {
    if (search.periodic[a] && search.length[a] < 3 * 2 * r_max) search.periodic[a] = false;
  }
  list.configure(search, r_max, 0.0, bed.n());
  const detail::ParticleView view{bed.x.data(), bed.y.data(), bed.z.data(), bed.radius.data(),
                                  bed.n()};
  list.build(view, 1);
  for (std::size_t i = 0; i < bed.n(); ++i) {
    for (const std::uint32_t* it = list.begin(i); it != list.end(i); ++it) {
      const std::size_t j = *it;  // j > i: a half list
      const double dx = box.image(0, bed.x[j] - bed.x[i]);
      const double dy = box.image(1, bed.y[j] - bed.y[i]);
      const double dz = box.image(2, bed.z[j] - bed.z[i]);
      const double reach = bed.radius[i] + bed.radius[j];
      const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (d < reach) f(i, j, reach - d, bed.radius[i] * bed.radius[j] / reach);
    }
  }
}

// Calls f(i, axis, side, delta) for each particle–wall overlap on non-periodic faces.
template <class F>
void for_each_wall_overlap(const bed::Bed& bed, F&& f) {
  const Box box = Box::from(bed.domain);
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double p[3] = {bed.x[i], bed.y[i], bed.z[i]};
    for (int a = 0; a < 3; ++a) {
      if (box.periodic[a]) continue;
      const double lower = bed.radius[i] - (p[a] - box.lower[a]);
      const double upper = bed.radius[i] - (box.upper[a] - p[a]);
      if (lower > 0) f(i, a, 0, lower);
      if (upper > 0) f(i, a, 1, upper);
    }
  }
}

HertzNormalParams pair_params(const Scene& s, double young_scale) {
  const double e = s.material.young / young_scale;
  return {effective_modulus(e, s.material.poisson, e, s.material.poisson),
          s.has(kDamping) ? s.material.damping : 0.0};
}

HertzNormalParams wall_params(const Scene& s, double young_scale) {
  return {effective_modulus(s.material.young / young_scale, s.material.poisson,
                            s.wall.young / young_scale, s.wall.poisson),
          s.has(kDamping) ? s.material.damping : 0.0};
}

}  // namespace

Energy energy(const bed::Bed& bed, const Scene& scene, double young_scale) {
  Energy e;
  const double rho = scene.material.density;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double m = mass_of(bed.radius[i], rho);
    if (bed.has_velocity()) {
      e.kinetic += 0.5 * m * (bed.vx[i] * bed.vx[i] + bed.vy[i] * bed.vy[i] + bed.vz[i] * bed.vz[i]);
    }
    if (scene.has(kGravity)) e.gravitational += m * scene.gravity * (bed.z[i] - bed.domain.lower[2]);
  }
  if (scene.has(kHertz)) {
    const HertzNormalParams p = pair_params(scene, young_scale);
    for_each_overlap(bed, [&](std::size_t, std::size_t, double delta, double r_star) {
      e.elastic += hertz_elastic_energy(p, r_star, delta);
    });
  }
  if (scene.has(kWalls)) {
    const HertzNormalParams p = wall_params(scene, young_scale);
    for_each_wall_overlap(bed, [&](std::size_t i, int, int, double delta) {
      e.elastic += hertz_elastic_energy(p, bed.radius[i], delta);
    });
  }
  return e;
}

std::array<double, 6> wall_forces(const bed::Bed& bed, const Scene& scene, double young_scale) {
  std::array<double, 6> f{};
  if (!scene.has(kWalls)) return f;
  const HertzNormalParams p = wall_params(scene, young_scale);
  for_each_wall_overlap(bed, [&](std::size_t i, int axis, int side, double delta) {
    const double v[3] = {bed.has_velocity() ? bed.vx[i] : 0.0, bed.has_velocity() ? bed.vy[i] : 0.0,
                         bed.has_velocity() ? bed.vz[i] : 0.0};
    const double rate = side == 0 ? -v[axis] : v[axis];
    const double m = mass_of(bed.radius[i], scene.material.density);
    f[static_cast<std::size_t>(2 * axis + side)] +=
        hertz_damped_force(p, bed.radius[i], m, delta, rate);
  });
  return f;
}

Overlap max_overlap(const bed::Bed& bed, const Scene& scene) {
  Overlap o;
  const auto note = [&](double delta, double r) {
    if (delta / r > o.relative) {
      o.relative = delta / r;
      o.absolute = delta;
    }
  };
  for_each_overlap(bed, [&](std::size_t i, std::size_t j, double delta, double) {
    note(delta, std::min(bed.radius[i], bed.radius[j]));
  });
  if (scene.has(kWalls)) {
    for_each_wall_overlap(bed, [&](std::size_t i, int, int, double delta) {
      note(delta, bed.radius[i]);
    });
  }
  return o;
}

}  // namespace powderbed::dem
