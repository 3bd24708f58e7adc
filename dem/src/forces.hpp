#pragma once
// The force loop, composed at compile time from the scene's effects (DESIGN.md "House style":
// a template over the chosen set, dispatched once; no per-contact test of a switch). Each
// particle sums its own forces over its full neighbour list, so the sum order is fixed and the
// result is the same for any thread count.
#include <cmath>
#include <cstddef>

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

template <unsigned E>
inline void wall_force(const ForceParams& p, int axis, double pos, double vel, double radius,
                       double mass, const double v[3], double f[3]) {
  const Box& box = p.box;
  if (box.periodic[axis]) return;
  // Lower face: overlap r - (x - lo), approach rate -v; upper: r - (hi - x), rate +v.
  for (int side = 0; side < 2; ++side) {
    const double gap = side == 0 ? pos - box.lower[axis] : box.upper[axis] - pos;
    const double delta = radius - gap;
    if (delta <= 0) continue;
    const double sign = side == 0 ? 1.0 : -1.0;  // direction of the push along the axis
    double fn;
    if constexpr ((E & kDamping) != 0) {
      fn = wall_damped_force(p.wall, radius, mass, delta, -sign * vel);
    } else {
      fn = wall_elastic_force(p.wall, radius, delta);
    }
    f[axis] += sign * fn;
    if constexpr ((E & kFriction) != 0) {
      double vt[3] = {v[0], v[1], v[2]};
      vt[axis] = 0;
      double ft[3];
      sliding_friction_force(p.friction, fn, vt[0], vt[1], vt[2], ft);
      f[0] += ft[0];
      f[1] += ft[1];
      f[2] += ft[2];
    }
  }
}

template <unsigned E>
void compute_forces(const ForceArrays& a, const ForceParams& p, const NeighbourList& list,
                    int threads) {
  for_each_particle(a.n, threads, [&](std::size_t i) {
    double f[3] = {0, 0, 0};
    const double v[3] = {a.vx[i], a.vy[i], a.vz[i]};
    if constexpr ((E & kGravity) != 0) f[2] += gravity_force_z(p.gravity, a.mass[i]);
    if constexpr ((E & kDrag) != 0) {
      f[0] -= a.drag[i] * v[0];
      f[1] -= a.drag[i] * v[1];
      f[2] -= a.drag[i] * v[2];
    }
    if constexpr ((E & kHertz) != 0) {
      const double ri = a.radius[i];
      for (const std::uint32_t* it = list.begin(i); it != list.end(i); ++it) {
        const std::uint32_t j = *it;
        const double dx = p.box.image(0, a.x[j] - a.x[i]);
        const double dy = p.box.image(1, a.y[j] - a.y[i]);
        const double dz = p.box.image(2, a.z[j] - a.z[i]);
        const double reach = ri + a.radius[j];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 >= reach * reach) continue;
        const double d = std::sqrt(d2);
        const double delta = reach - d;
        const double inv_d = 1.0 / d;
        const double nx = dx * inv_d, ny = dy * inv_d, nz = dz * inv_d;  // from i to j
        const double r_star = ri * a.radius[j] / reach;
        double fn;
        [[maybe_unused]] double wx = 0, wy = 0, wz = 0, rate = 0;  // relative velocity v_i - v_j
        if constexpr ((E & (kDamping | kFriction)) != 0) {
          wx = v[0] - a.vx[j];
          wy = v[1] - a.vy[j];
          wz = v[2] - a.vz[j];
          rate = wx * nx + wy * ny + wz * nz;
        }
        if constexpr ((E & kDamping) != 0) {
          const double m_star = a.mass[i] * a.mass[j] / (a.mass[i] + a.mass[j]);
          fn = hertz_damped_force(p.pair, r_star, m_star, delta, rate);
        } else {
          fn = hertz_elastic_force(p.pair, r_star, delta);
        }
        f[0] -= fn * nx;
        f[1] -= fn * ny;
        f[2] -= fn * nz;
        if constexpr ((E & kFriction) != 0) {
          double ft[3];
          sliding_friction_force(p.friction, fn, wx - rate * nx, wy - rate * ny, wz - rate * nz,
                                 ft);
          f[0] += ft[0];
          f[1] += ft[1];
          f[2] += ft[2];
        }
      }
    }
    if constexpr ((E & kWalls) != 0) {
      const double pos[3] = {a.x[i], a.y[i], a.z[i]};
      for (int axis = 0; axis < 3; ++axis) {
        wall_force<E>(p, axis, pos[axis], v[axis], a.radius[i], a.mass[i], v, f);
      }
    }
    a.fx[i] = f[0];
    a.fy[i] = f[1];
    a.fz[i] = f[2];
  });
}

}  // namespace powderbed::dem::detail
