#include "powderbed/dem/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "box.hpp"
#include "neighbour_list.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/dem/contact_moduli.hpp"
#include "powderbed/dem/hertz_normal.hpp"
#include "powderbed/dem/linear_normal.hpp"

namespace powderbed::dem {

namespace {

using detail::Box;

double mass_of(double radius, double density) {
  return bed::sphere_volume(radius) * density;
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
  return {contact_moduli(s, young_scale).pair, s.has(kDamping) ? s.material.damping : 0.0};
}

HertzNormalParams wall_params(const Scene& s, double young_scale) {
  return {contact_moduli(s, young_scale).wall, s.has(kDamping) ? s.material.damping : 0.0};
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
  const bool linear = scene.law == ContactLaw::linear;
  const LinearNormalParams spring{scene.stiffness, 0.0};
  if (scene.has(kHertz)) {
    const HertzNormalParams p = pair_params(scene, young_scale);
    for_each_overlap(bed, [&](std::size_t, std::size_t, double delta, double r_star) {
      e.elastic += linear ? linear_elastic_energy(spring, delta)
                          : hertz_elastic_energy(p, r_star, delta);
    });
  }
  if (scene.has(kWalls)) {
    const HertzNormalParams p = wall_params(scene, young_scale);
    for_each_wall_overlap(bed, [&](std::size_t i, int, int, double delta) {
      e.elastic += linear ? linear_elastic_energy(spring, delta)
                          : hertz_elastic_energy(p, bed.radius[i], delta);
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
        scene.law == ContactLaw::linear
            ? linear_damped_force(linear_pair_constants({scene.stiffness, p.damping_ratio}, m),
                                  delta, rate)
            : hertz_damped_force(p, bed.radius[i], m, delta, rate);
  });
  return f;
}

double full_stiffness_overlap(const Overlap& overlap, const Scene& scene, double young_scale) {
  if (scene.law == ContactLaw::hertz) return bed::hertz_overlap_of_softened(overlap.relative, young_scale);
  if (!(overlap.absolute > 0)) return 0.0;
  const ContactModuli moduli = contact_moduli(scene, young_scale);
  const double full = bed::hertz_overlap_of_linear(overlap.absolute, scene.stiffness,
                                                   overlap.wall ? moduli.wall : moduli.pair, overlap.reduced_radius);
  return overlap.relative * full / overlap.absolute;
}

Overlap max_overlap(const bed::Bed& bed, const Scene& scene) {
  Overlap o;
  const auto note = [&](double delta, double r, double r_star, bool wall) {
    if (delta / r > o.relative) {
      o.relative = delta / r;
      o.absolute = delta;
      o.reduced_radius = r_star;
      o.wall = wall;
    }
  };
  for_each_overlap(bed, [&](std::size_t i, std::size_t j, double delta, double r_star) {
    note(delta, std::min(bed.radius[i], bed.radius[j]), r_star, false);
    ++o.contacts;
  });
  if (scene.has(kWalls)) {
    for_each_wall_overlap(bed, [&](std::size_t i, int, int, double delta) {
      note(delta, bed.radius[i], bed.radius[i], true);
      ++o.contacts;
    });
  }
  return o;
}

std::size_t count_outside(const bed::Bed& bed, std::size_t n) {
  const Box box = Box::from(bed.domain);
  std::size_t outside = 0;
  for (std::size_t i = 0; i < std::min(n, bed.n()); ++i) {
    const double p[3] = {bed.x[i], bed.y[i], bed.z[i]};
    for (int a = 0; a < 3; ++a) {
      if (!box.periodic[a] && (p[a] < box.lower[a] || p[a] > box.upper[a])) {
        ++outside;
        break;
      }
    }
  }
  return outside;
}

ThermoRow thermo_row(const bed::Bed& bed, const Scene& scene, std::size_t n) {
  ThermoRow row;
  row.lost = count_outside(bed, n);
  if (n >= bed.n()) {
    row.overlap = max_overlap(bed, scene);
    return row;
  }
  bed::Bed head;  // an insertion's pool beyond the first n waits, overlapping, at the centre
  head.domain = bed.domain;
  head.reserve(n);
  for (std::size_t i = 0; i < n; ++i) head.add(bed.x[i], bed.y[i], bed.z[i], bed.radius[i]);
  row.overlap = max_overlap(head, scene);
  return row;
}

CoreDensity core_density(const bed::Bed& bed, double margin) {
  CoreDensity core;
  const Box box = Box::from(bed.domain);
  std::vector<double> tops(bed.n());
  for (std::size_t i = 0; i < bed.n(); ++i) tops[i] = bed.z[i] + bed.radius[i];
  double surface = box.lower[2];
  if (!tops.empty()) {
    const auto k = tops.begin() + static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(tops.size() - 1));
    std::nth_element(tops.begin(), k, tops.end());
    surface = *k;
  }
  for (int a = 0; a < 3; ++a) {
    core.lower[a] = box.lower[a] + (box.periodic[a] ? 0.0 : margin);
    core.upper[a] = box.upper[a] - (box.periodic[a] ? 0.0 : margin);
  }
  core.upper[2] = std::min(core.upper[2], surface - margin);
  double volume = 1;
  for (int a = 0; a < 3; ++a) volume *= std::max(0.0, core.upper[a] - core.lower[a]);
  if (!(volume > 0) || bed.n() == 0) {
    core.density = std::numeric_limits<double>::quiet_NaN();
    return core;
  }
  const double r_min = *std::min_element(bed.radius.begin(), bed.radius.end());
  const double h = std::max(r_min / 10, std::cbrt(volume / 2e7));
  std::size_t cells[3];
  double step[3];
  for (int a = 0; a < 3; ++a) {
    cells[a] = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil((core.upper[a] - core.lower[a]) / h)));
    step[a] = (core.upper[a] - core.lower[a]) / static_cast<double>(cells[a]);
  }
  std::vector<std::uint8_t> solid(cells[0] * cells[1] * cells[2], 0);
  // Index range of the cell centres lower + (k + 1/2) step within [lo, hi] along axis a.
  const auto range = [&](int a, double lo, double hi, std::ptrdiff_t& first, std::ptrdiff_t& last) {
    first = std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>(std::ceil((lo - core.lower[a]) / step[a] - 0.5)));
    last = std::min<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(cells[a]) - 1,
                                    static_cast<std::ptrdiff_t>(std::floor((hi - core.lower[a]) / step[a] - 0.5)));
  };
  const auto mark = [&](double cx, double cy, double cz, double r) {
    std::ptrdiff_t x0, x1, y0, y1;
    range(0, cx - r, cx + r, x0, x1);
    range(1, cy - r, cy + r, y0, y1);
    for (std::ptrdiff_t ix = x0; ix <= x1; ++ix) {
      const double dx = core.lower[0] + (static_cast<double>(ix) + 0.5) * step[0] - cx;
      for (std::ptrdiff_t iy = y0; iy <= y1; ++iy) {
        const double dy = core.lower[1] + (static_cast<double>(iy) + 0.5) * step[1] - cy;
        const double chord2 = r * r - dx * dx - dy * dy;
        if (chord2 < 0) continue;
        const double half = std::sqrt(chord2);
        std::ptrdiff_t z0, z1;
        range(2, cz - half, cz + half, z0, z1);
        const std::size_t column = (static_cast<std::size_t>(ix) * cells[1] + static_cast<std::size_t>(iy)) * cells[2];
        for (std::ptrdiff_t iz = z0; iz <= z1; ++iz) solid[column + static_cast<std::size_t>(iz)] = 1;
      }
    }
  };
  for (std::size_t i = 0; i < bed.n(); ++i) {
    // Periodic images of spheres that cross a periodic face.
    for (int sx = -1; sx <= 1; ++sx) {
      if (sx != 0 && !box.periodic[0]) continue;
      for (int sy = -1; sy <= 1; ++sy) {
        if (sy != 0 && !box.periodic[1]) continue;
        mark(bed.x[i] + sx * box.length[0], bed.y[i] + sy * box.length[1], bed.z[i], bed.radius[i]);
      }
    }
  }
  std::size_t count = 0;
  for (const std::uint8_t v : solid) count += v;
  core.density = static_cast<double>(count) / static_cast<double>(solid.size());
  return core;
}

}  // namespace powderbed::dem
