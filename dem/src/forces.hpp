#pragma once
// The force loop, composed at compile time from the scene's effects (docs/architecture.md "House style":
// a template over the chosen set, dispatched once; no per-contact test of a switch). Each
// contact force is computed once per pair (half neighbour list) from constants tabulated at the
// list build, and the forces on a particle are summed in one fixed order (body forces, walls,
// then its pairs in NeighbourList's incident order) for any thread count: serially by adding
// F to i and subtracting it from j, in parallel by storing each pair's F and gathering.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "box.hpp"
#include "contact_kernel.hpp"
#include "neighbour_list.hpp"
#include "parallel.hpp"
#include "powderbed/dem/gravity.hpp"
#include "normal_law.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/sliding_friction.hpp"

namespace powderbed::dem::detail {

struct ForceParams {
  NormalLawParams pair;     // particle–particle: Hertz E*, zeta; linear k_n, zeta
  NormalLawParams wall;     // particle–wall: the same with the wall's E*
  SlidingFrictionParams friction;
  GravityParams gravity;
  Box box;
  // z velocity of the box's top face: the lid while it is lowered (solver.hpp LidSettings);
  // 0 otherwise, when the subtraction below leaves every approach rate bit for bit unchanged.
  double top_velocity = 0;
  // For the per-contact E* of stiffness-scaled fines (ForceArrays::young): the particles' and
  // the wall's nu and the wall's (softened) E, Pa.
  double poisson = 0, wall_poisson = 0, wall_young = 0;
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
  const double* mass;    // inertial mass (the fines' scaled one under mass scaling), kg
  const double* weight;  // the mass gravity acts on: the physical one (== mass without scaling)
  const double* drag;    // 6 pi mu_f r per particle
  // Per-particle E (Pa) under fines stiffness scaling, whose contacts take E* from their two
  // moduli at the tabulation; nullptr: every contact has the scene's E* (ForceParams).
  const double* young;
  double* fx;
  double* fy;
  double* fz;
  std::size_t n;
};

// Constants of the contact laws, refreshed at each neighbour-list build (pairs, wall faces) or
// once per run (per-particle wall constants), and the pair forces of a parallel sum.
struct ContactTables {
  std::vector<double> reach;                   // per pair: r_i + r_j
  std::vector<NormalConstants> pair;           // per pair
  std::vector<NormalConstants> wall;           // per particle (R* = r_i, m* = m_i)
  // Per particle, bit 2 axis + side set when that face may be touched before the next build:
  // its gap at the build is below r + skin (a particle moves at most skin/2 between builds).
  std::vector<std::uint8_t> wall_faces;
  std::array<std::vector<std::uint32_t>, 6> face_particles;  // per face: its bit set, i ascending
  std::vector<double> pfx, pfy, pfz;           // per pair: force on the lower index (threads > 1)
  std::vector<ContactBuffer> buffers = std::vector<ContactBuffer>(1);  // one per thread
};

// The law's parameters of a contact of particles i and j: the scene's, or with stiffness-
// scaled fines E* = 1 / ((1 - nu^2)/E_i + (1 - nu^2)/E_j) of the two particles' moduli.
inline NormalLawParams pair_params(const ForceArrays& a, const ForceParams& p, std::size_t i,
                                   std::size_t j) {
  NormalLawParams law = p.pair;
  if (a.young != nullptr) {
    law.hertz.effective_modulus = effective_modulus(a.young[i], p.poisson, a.young[j], p.poisson);
  }
  return law;
}

// The same for particle i on a wall: E* of its E_i and the wall's E.
inline NormalLawParams wall_params(const ForceArrays& a, const ForceParams& p, std::size_t i) {
  NormalLawParams law = p.wall;
  if (a.young != nullptr) {
    law.hertz.effective_modulus =
        effective_modulus(a.young[i], p.poisson, p.wall_young, p.wall_poisson);
  }
  return law;
}

// Per-particle wall constants, once per run.
template <class Law>
void tabulate_wall_constants(ContactTables& t, const ForceArrays& a, const ForceParams& p) {
  t.wall.resize(a.n);
  for (std::size_t i = 0; i < a.n; ++i) {
    t.wall[i] = Law::constants(wall_params(a, p, i), a.radius[i], a.mass[i]);
  }
  t.wall_faces.assign(a.n, 0);
}

// Pair constants and wall faces after a neighbour-list build.
template <class Law>
void tabulate_contacts(ContactTables& t, const ForceArrays& a, const ForceParams& p,
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
      t.pair[k] = Law::constants(pair_params(a, p, i, j), ri * a.radius[j] / reach,
                                 mi * a.mass[j] / (mi + a.mass[j]));
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
  for (std::size_t face = 0; face < 6; ++face) {
    t.face_particles[face].clear();
    for (std::size_t i = 0; i < a.n; ++i) {
      if ((t.wall_faces[i] & (1u << face)) != 0) {
        t.face_particles[face].push_back(static_cast<std::uint32_t>(i));
      }
    }
  }
}

// Contact of particle i with face (Axis, Side) of the box (docs/physics.md §4: the scene's law with
// R* = r_i, m* = m_i), added to f. Axis and side are compile-time, so position, velocity and
// force stay in registers.
template <unsigned E, class Law, int Axis, int Side>
inline void wall_face(const ForceParams& p, const ContactTables& t, std::size_t i,
                      const double pos[3], const double v[3], double radius, double f[3]) {
  // Lower face: overlap r - (x - lo), approach rate -v; upper: r - (hi - x), rate +v (the top
  // face's rate relative to the face, which moves while it is the lid).
  const double gap = Side == 0 ? pos[Axis] - p.box.lower[Axis] : p.box.upper[Axis] - pos[Axis];
  const double delta = radius - gap;
  if (delta <= 0) return;
  constexpr double sign = Side == 0 ? 1.0 : -1.0;  // direction of the push along the axis
  double fn;
  if constexpr ((E & kDamping) != 0) {
    double rate = -sign * v[Axis];
    if constexpr (Axis == 2 && Side == 1) rate -= p.top_velocity;
    fn = Law::damped(t.wall[i].elastic, t.wall[i].damping, delta, rate);
  } else {
    fn = Law::elastic(t.wall[i].elastic, delta);
  }
  f[Axis] += sign * fn;
  if constexpr ((E & kFriction) != 0) {
    double ft[3];
    sliding_friction_force(p.friction, Law::normal_magnitude(fn), Axis == 0 ? 0.0 : v[0], Axis == 1 ? 0.0 : v[1],
                           Axis == 2 ? 0.0 : v[2], ft);
    f[0] += ft[0];
    f[1] += ft[1];
    f[2] += ft[2];
  }
}

// Contacts with face (Axis, Side) of the particles of [begin, end) that may touch it, added to
// their forces.
template <unsigned E, class Law, int Axis, int Side>
void face_forces(const ForceArrays& a, const ForceParams& p, const ContactTables& t,
                 std::size_t begin, std::size_t end) {
  const std::vector<std::uint32_t>& near = t.face_particles[2 * Axis + Side];  // i ascending
  const auto first = std::lower_bound(near.begin(), near.end(), begin);
  const auto last = std::lower_bound(first, near.end(), end);
  for (auto it = first; it != last; ++it) {
    const std::uint32_t i = *it;
    const double v[3] = {a.vx[i], a.vy[i], a.vz[i]};
    const double pos[3] = {a.x[i], a.y[i], a.z[i]};
    double f[3] = {a.fx[i], a.fy[i], a.fz[i]};
    wall_face<E, Law, Axis, Side>(p, t, i, pos, v, a.radius[i], f);
    a.fx[i] = f[0];
    a.fy[i] = f[1];
    a.fz[i] = f[2];
  }
}

// Separation along `axis`, with the minimum image only when some axis is periodic (the
// branch is hoisted out of the loops by instantiating them for both cases).
template <bool Periodic>
inline double separation(const Box& box, int axis, double delta) {
  if constexpr (Periodic) {
    return box.image(axis, delta);
  } else {
    return delta;
  }
}

// Pass 1 over the pairs of particles [begin, end), one flat loop over list entries: the pairs k
// with |x_j - x_i| < r_i + r_j, then their separations, velocity differences and constants.
template <unsigned E, bool Periodic>
void collect_contacts(const ForceArrays& a, const Box& box, const ContactTables& t,
                      const NeighbourList& list, std::size_t begin, std::size_t end,
                      ContactBuffer& b) {
  const std::size_t k0 = list.offset(begin), k1 = list.offset(end);
  b.reserve(k1 - k0);
  const std::uint32_t* __restrict owner = list.owners();
  const std::uint32_t* __restrict partner = list.partners();
  const double* __restrict x = a.x;
  const double* __restrict y = a.y;
  const double* __restrict z = a.z;
  const double* __restrict table_reach = t.reach.data();
  std::uint32_t* __restrict bk = b.k.data();
  std::size_t m = 0;
  for (std::size_t k = k0; k < k1; ++k) {
    const std::uint32_t i = owner[k], j = partner[k];
    const double ex = separation<Periodic>(box, 0, x[j] - x[i]);
    const double ey = separation<Periodic>(box, 1, y[j] - y[i]);
    const double ez = separation<Periodic>(box, 2, z[j] - z[i]);
    const double r = table_reach[k];
    bk[m] = static_cast<std::uint32_t>(k);
    m += static_cast<std::size_t>(ex * ex + ey * ey + ez * ez < r * r);
  }
  b.count = m;
  for (std::size_t c = 0; c < m; ++c) {
    const std::uint32_t k = bk[c], i = owner[k], j = partner[k];
    b.i[c] = i;
    b.j[c] = j;
    b.dx[c] = separation<Periodic>(box, 0, x[j] - x[i]);
    b.dy[c] = separation<Periodic>(box, 1, y[j] - y[i]);
    b.dz[c] = separation<Periodic>(box, 2, z[j] - z[i]);
    b.reach[c] = table_reach[k];
    b.elastic[c] = t.pair[k].elastic;
    if constexpr ((E & kDamping) != 0) b.damping[c] = t.pair[k].damping;
    if constexpr ((E & (kDamping | kFriction)) != 0) {
      b.dvx[c] = a.vx[i] - a.vx[j];
      b.dvy[c] = a.vy[i] - a.vy[j];
      b.dvz[c] = a.vz[i] - a.vz[j];
    }
  }
}

template <unsigned E>
void collect_contacts(const ForceArrays& a, const ForceParams& p, const ContactTables& t,
                      const NeighbourList& list, std::size_t begin, std::size_t end,
                      ContactBuffer& b) {
  if (p.box.any_periodic()) {
    collect_contacts<E, true>(a, p.box, t, list, begin, end, b);
  } else {
    collect_contacts<E, false>(a, p.box, t, list, begin, end, b);
  }
}

template <unsigned E, class Law>
void contact_forces(const ForceParams& p, ContactBuffer& b) {
  contact_kernel<E, Law>(b.count, p.friction, b.dx.data(), b.dy.data(), b.dz.data(), b.reach.data(),
                    b.elastic.data(), b.damping.data(), b.dvx.data(), b.dvy.data(), b.dvz.data(),
                    b.fx.data(), b.fy.data(), b.fz.data());
}

// Gravity and drag on particles [begin, end), starting each particle's force from 0: a plain
// loop the compiler vectorises.
template <unsigned E>
void body_forces(const ForceArrays& a, const ForceParams& p, std::size_t begin, std::size_t end) {
  double* __restrict fx = a.fx;
  double* __restrict fy = a.fy;
  double* __restrict fz = a.fz;
  const double* __restrict weight = a.weight;
  const double* __restrict drag = a.drag;
  const double* __restrict vx = a.vx;
  const double* __restrict vy = a.vy;
  const double* __restrict vz = a.vz;
  for (std::size_t i = begin; i < end; ++i) {
    double f[3] = {0, 0, 0};
    if constexpr ((E & kGravity) != 0) f[2] += gravity_force_z(p.gravity, weight[i]);
    if constexpr ((E & kDrag) != 0) {
      f[0] -= drag[i] * vx[i];
      f[1] -= drag[i] * vy[i];
      f[2] -= drag[i] * vz[i];
    }
    fx[i] = f[0];
    fy[i] = f[1];
    fz[i] = f[2];
  }
}

// Forces on every particle (docs/physics.md §4), summed in one fixed order for any thread count: body
// forces, walls, then the particle's pairs in NeighbourList's incident order.
template <unsigned E, class Law>
void compute_forces(const ForceArrays& a, const ForceParams& p, const NeighbourList& list,
                    ContactTables& t, int threads) {
  // Body forces, then walls face by face, so every particle adds its faces in the same order;
  // one parallel region (each fork and barrier costs microseconds, far more on a busy machine).
  for_each_chunk(a.n, threads, [&](std::size_t begin, std::size_t end) {
    body_forces<E>(a, p, begin, end);
    if constexpr ((E & kWalls) != 0) {
      face_forces<E, Law, 0, 0>(a, p, t, begin, end);
      face_forces<E, Law, 0, 1>(a, p, t, begin, end);
      face_forces<E, Law, 1, 0>(a, p, t, begin, end);
      face_forces<E, Law, 1, 1>(a, p, t, begin, end);
      face_forces<E, Law, 2, 0>(a, p, t, begin, end);
      face_forces<E, Law, 2, 1>(a, p, t, begin, end);
    }
  });
  if constexpr ((E & kHertz) != 0) {
    if (threads <= 1) {
      ContactBuffer& b = t.buffers[0];
      for (std::size_t begin = 0; begin < a.n; begin += kContactBlock) {
        collect_contacts<E>(a, p, t, list, begin, std::min(a.n, begin + kContactBlock), b);
        contact_forces<E, Law>(p, b);
        // In list order, i ascending: every particle meets its pairs in incident order.
        for (std::size_t c = 0; c < b.count; ++c) {
          const std::uint32_t i = b.i[c], j = b.j[c];
          a.fx[i] += b.fx[c];
          a.fy[i] += b.fy[c];
          a.fz[i] += b.fz[c];
          a.fx[j] -= b.fx[c];
          a.fy[j] -= b.fy[c];
          a.fz[j] -= b.fz[c];
        }
      }
      return;
    }
    t.buffers.resize(static_cast<std::size_t>(threads));
    for_each_chunk(a.n, threads, [&](std::size_t chunk_begin, std::size_t chunk_end) {
      ContactBuffer& b = t.buffers[static_cast<std::size_t>(omp_get_thread_num())];
      const auto first = static_cast<std::ptrdiff_t>(list.offset(chunk_begin));
      const auto last = static_cast<std::ptrdiff_t>(list.offset(chunk_end));
      std::fill(t.pfx.begin() + first, t.pfx.begin() + last, 0.0);
      std::fill(t.pfy.begin() + first, t.pfy.begin() + last, 0.0);
      std::fill(t.pfz.begin() + first, t.pfz.begin() + last, 0.0);
      for (std::size_t begin = chunk_begin; begin < chunk_end; begin += kContactBlock) {
        collect_contacts<E>(a, p, t, list, begin, std::min(chunk_end, begin + kContactBlock), b);
        contact_forces<E, Law>(p, b);
        for (std::size_t c = 0; c < b.count; ++c) {
          t.pfx[b.k[c]] = b.fx[c];
          t.pfy[b.k[c]] = b.fy[c];
          t.pfz[b.k[c]] = b.fz[c];
        }
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
