#pragma once
// The force loop, composed at compile time from the scene's effects (DESIGN.md "House style":
// a template over the chosen set, dispatched once; no per-contact test of a switch). Each
// contact force is computed once per pair (half neighbour list) from constants tabulated at the
// list build, and the forces on a particle are summed in one fixed order (body forces, walls,
// then its pairs in NeighbourList's incident order) for any thread count: serially by adding
// F to i and subtracting it from j, in parallel by storing each pair's F and gathering.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "box.hpp"
#include "neighbour_list.hpp"
#include "parallel.hpp"
#include "powderbed/dem/gravity.hpp"
#include "powderbed/dem/hertz_normal.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/sliding_friction.hpp"
#include "powderbed/dem/walls.hpp"

namespace powderbed::dem::detail {

struct ForceParams {
  HertzNormalParams pair;   // particle–particle E*, zeta
  HertzNormalParams wall;   // particle–wall E*, zeta
  SlidingFrictionParams friction;
  GravityParams gravity;
  Box box;
};

// Positions and velocities in (the current RK4 stage or the Verlet half step), forces out.
struct ForceArrays {
  const double* x;
  const double* y;
  const double* z;
  const double* vx;
  const double* vy;
  const double* vz;
  const double* radius;
  const double* mass;
  const double* drag;  // 6 pi mu_f r per particle
  double* fx;
  double* fy;
  double* fz;
  std::size_t n;
};

// Constants of the contact laws, refreshed at each neighbour-list build (pairs, wall faces) or
// once per run (per-particle wall constants), and the pair forces of a parallel sum.
struct ContactTables {
  std::vector<double> reach;                   // per pair: r_i + r_j
  std::vector<HertzPairConstants> pair;        // per pair
  std::vector<HertzPairConstants> wall;        // per particle (R* = r_i, m* = m_i)
  // Per particle, bit 2 axis + side set when that face may be touched before the next build:
  // its gap at the build is below r + skin (a particle moves at most skin/2 between builds).
  std::vector<std::uint8_t> wall_faces;
  std::vector<double> pfx, pfy, pfz;           // per pair: force on the lower index (threads > 1)
};

// Per-particle wall constants, once per run.
inline void tabulate_wall_constants(ContactTables& t, const ForceArrays& a, const ForceParams& p) {
  t.wall.resize(a.n);
  for (std::size_t i = 0; i < a.n; ++i) t.wall[i] = hertz_pair_constants(p.wall, a.radius[i], a.mass[i]);
  t.wall_faces.assign(a.n, 0);
}

// Pair constants and wall faces after a neighbour-list build.
inline void tabulate_contacts(ContactTables& t, const ForceArrays& a, const ForceParams& p,
                              const NeighbourList& list, double skin, int threads) {
  const std::size_t pairs = list.pair_entries();
  t.reach.resize(pairs);
  t.pair.resize(pairs);
  if (threads > 1) {
    t.pfx.resize(pairs);
    t.pfy.resize(pairs);
    t.pfz.resize(pairs);
  }
  const Box& box = p.box;
  for_each_particle(a.n, threads, [&](std::size_t i) {
    const double ri = a.radius[i], mi = a.mass[i];
    std::size_t k = list.offset(i);
    for (const std::uint32_t* it = list.begin(i); it != list.end(i); ++it, ++k) {
      const std::uint32_t j = *it;
      const double reach = ri + a.radius[j];
      t.reach[k] = reach;
      t.pair[k] = hertz_pair_constants(p.pair, ri * a.radius[j] / reach, mi * a.mass[j] / (mi + a.mass[j]));
    }
    const double pos[3] = {a.x[i], a.y[i], a.z[i]};
    std::uint8_t faces = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (box.periodic[axis]) continue;
      if (pos[axis] - box.lower[axis] < ri + skin) faces |= static_cast<std::uint8_t>(1u << (2 * axis));
      if (box.upper[axis] - pos[axis] < ri + skin) faces |= static_cast<std::uint8_t>(1u << (2 * axis + 1));
    }
    t.wall_faces[i] = faces;
  });
}

// Contact of particle i with face (Axis, Side) of the box (SPEC §4: the Hertz law with R* = r_i,
// m* = m_i), added to f. Axis and side are compile-time, so position, velocity and force stay in
// registers.
template <unsigned E, int Axis, int Side>
inline void wall_face(const ForceParams& p, const ContactTables& t, std::size_t i,
                      const double pos[3], const double v[3], double radius, double f[3]) {
  // Lower face: overlap r - (x - lo), approach rate -v; upper: r - (hi - x), rate +v.
  const double gap = Side == 0 ? pos[Axis] - p.box.lower[Axis] : p.box.upper[Axis] - pos[Axis];
  const double delta = radius - gap;
  if (delta <= 0) return;
  constexpr double sign = Side == 0 ? 1.0 : -1.0;  // direction of the push along the axis
  double fn;
  if constexpr ((E & kDamping) != 0) {
    fn = hertz_damped_force(t.wall[i], delta, -sign * v[Axis]);
  } else {
    fn = hertz_elastic_force(t.wall[i], delta);
  }
  f[Axis] += sign * fn;
  if constexpr ((E & kFriction) != 0) {
    double ft[3];
    sliding_friction_force(p.friction, fn, Axis == 0 ? 0.0 : v[0], Axis == 1 ? 0.0 : v[1],
                           Axis == 2 ? 0.0 : v[2], ft);
    f[0] += ft[0];
    f[1] += ft[1];
    f[2] += ft[2];
  }
}

// Gravity, drag and walls on particle i (SPEC §4), into f.
template <unsigned E>
inline void particle_forces(const ForceArrays& a, const ForceParams& p, const ContactTables& t,
                            std::size_t i, double f[3]) {
  const double v[3] = {a.vx[i], a.vy[i], a.vz[i]};
  f[0] = 0;
  f[1] = 0;
  f[2] = 0;
  if constexpr ((E & kGravity) != 0) f[2] += gravity_force_z(p.gravity, a.mass[i]);
  if constexpr ((E & kDrag) != 0) {
    f[0] -= a.drag[i] * v[0];
    f[1] -= a.drag[i] * v[1];
    f[2] -= a.drag[i] * v[2];
  }
  if constexpr ((E & kWalls) != 0) {
    const unsigned faces = t.wall_faces[i];
    if (faces == 0) return;
    const double pos[3] = {a.x[i], a.y[i], a.z[i]};
    const double r = a.radius[i];
    if ((faces & 1u) != 0) wall_face<E, 0, 0>(p, t, i, pos, v, r, f);
    if ((faces & 2u) != 0) wall_face<E, 0, 1>(p, t, i, pos, v, r, f);
    if ((faces & 4u) != 0) wall_face<E, 1, 0>(p, t, i, pos, v, r, f);
    if ((faces & 8u) != 0) wall_face<E, 1, 1>(p, t, i, pos, v, r, f);
    if ((faces & 16u) != 0) wall_face<E, 2, 0>(p, t, i, pos, v, r, f);
    if ((faces & 32u) != 0) wall_face<E, 2, 1>(p, t, i, pos, v, r, f);
  }
}

// Force F on i from pair k = (i, j) (j gets -F); false, F untouched, when they do not touch.
template <unsigned E>
inline bool pair_force(const ForceArrays& a, const ForceParams& p, const ContactTables& t,
                       std::size_t i, std::size_t j, std::size_t k, double f[3]) {
  const double dx = p.box.image(0, a.x[j] - a.x[i]);
  const double dy = p.box.image(1, a.y[j] - a.y[i]);
  const double dz = p.box.image(2, a.z[j] - a.z[i]);
  const double reach = t.reach[k];
  const double d2 = dx * dx + dy * dy + dz * dz;
  if (d2 >= reach * reach) return false;
  const double d = std::sqrt(d2);
  const double delta = reach - d;
  const double inv_d = 1.0 / d;
  const double nx = dx * inv_d, ny = dy * inv_d, nz = dz * inv_d;  // from i to j
  double fn;
  [[maybe_unused]] double wx = 0, wy = 0, wz = 0, rate = 0;  // relative velocity v_i - v_j
  if constexpr ((E & (kDamping | kFriction)) != 0) {
    wx = a.vx[i] - a.vx[j];
    wy = a.vy[i] - a.vy[j];
    wz = a.vz[i] - a.vz[j];
    rate = wx * nx + wy * ny + wz * nz;
  }
  if constexpr ((E & kDamping) != 0) {
    fn = hertz_damped_force(t.pair[k], delta, rate);
  } else {
    fn = hertz_elastic_force(t.pair[k], delta);
  }
  f[0] = -fn * nx;
  f[1] = -fn * ny;
  f[2] = -fn * nz;
  if constexpr ((E & kFriction) != 0) {
    double ft[3];
    sliding_friction_force(p.friction, fn, wx - rate * nx, wy - rate * ny, wz - rate * nz, ft);
    f[0] += ft[0];
    f[1] += ft[1];
    f[2] += ft[2];
  }
  return true;
}

template <unsigned E>
void compute_forces(const ForceArrays& a, const ForceParams& p, const NeighbourList& list,
                    ContactTables& t, int threads) {
  for_each_particle(a.n, threads, [&](std::size_t i) {
    double f[3];
    particle_forces<E>(a, p, t, i, f);
    a.fx[i] = f[0];
    a.fy[i] = f[1];
    a.fz[i] = f[2];
  });
  if constexpr ((E & kHertz) != 0) {
    if (threads <= 1) {
      for (std::size_t i = 0; i < a.n; ++i) {
        double fi[3] = {a.fx[i], a.fy[i], a.fz[i]};
        std::size_t k = list.offset(i);
        for (const std::uint32_t* it = list.begin(i); it != list.end(i); ++it, ++k) {
          double f[3];
          if (!pair_force<E>(a, p, t, i, *it, k, f)) continue;
          fi[0] += f[0];
          fi[1] += f[1];
          fi[2] += f[2];
          a.fx[*it] -= f[0];
          a.fy[*it] -= f[1];
          a.fz[*it] -= f[2];
        }
        a.fx[i] = fi[0];
        a.fy[i] = fi[1];
        a.fz[i] = fi[2];
      }
      return;
    }
    for_each_particle(a.n, threads, [&](std::size_t i) {
      std::size_t k = list.offset(i);
      for (const std::uint32_t* it = list.begin(i); it != list.end(i); ++it, ++k) {
        double f[3] = {0, 0, 0};
        pair_force<E>(a, p, t, i, *it, k, f);
        t.pfx[k] = f[0];
        t.pfy[k] = f[1];
        t.pfz[k] = f[2];
      }
    });
    // Same additions in the same order as the serial loop (a pair not in contact adds 0).
    for_each_particle(a.n, threads, [&](std::size_t i) {
      double fi[3] = {a.fx[i], a.fy[i], a.fz[i]};
      for (const std::uint32_t* e = list.incident_begin(i); e != list.incident_end(i); ++e) {
        const std::uint32_t k = *e >> 1;
        if ((*e & 1u) != 0) {
          fi[0] += t.pfx[k];
          fi[1] += t.pfy[k];
          fi[2] += t.pfz[k];
        } else {
          fi[0] -= t.pfx[k];
          fi[1] -= t.pfy[k];
          fi[2] -= t.pfz[k];
        }
      }
      a.fx[i] = fi[0];
      a.fy[i] = fi[1];
      a.fz[i] = fi[2];
    });
  }
}

}  // namespace powderbed::dem::detail
