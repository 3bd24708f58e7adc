#pragma once
// Static friction: a tangential spring with history, capped at mu F_n (Cundall & Strack 1979;
// Mindlin 1949 for the Hertz law's stiffness; as LIGGGHTS's `tangential history` and LAMMPS's
// `tangential mindlin` with its force history). The contact stores the spring's elastic force
// F_s, built up incrementally from the tangential slip, so that a stiffness that grows with the
// overlap (Mindlin) never creates energy from slip that happened under a smaller one; docs/
// deposit-spread.md gives the equations.
#include <cmath>

// The Hertz law's k_t (Mindlin) and G*, which the spring below takes.
#include "powderbed/dem/mindlin_tangential.hpp"

namespace powderbed::dem {

// Turns a stored tangential vector onto the plane normal to the current unit normal n,
// keeping its length (the contact frame rotates with the pair; Luding 2008, eq. 17).
// The projection alone shortens |v|^2 by along^2. A contact at rest turns by ~1e-8 rad a step,
// so the rescale would change the length by ~1e-16, below round-off, yet its root and division
// are a third of a settled bed's contact cost: it is left out while along^2 <= 1e-12 |v|^2 (a
// turn below 1e-6 rad). At that bound every step a million steps shorten the spring by less
// than 1e-6 of its length.
inline void rotate_onto_tangent_plane(double v[3], const double n[3]) {
  const double along = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  if (along == 0.0) return;
  const double before = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];  // squared lengths: one root
  for (int a = 0; a < 3; ++a) v[a] -= along * n[a];
  if (along * along <= 1e-12 * before) return;
  const double after = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double scale = after > 0.0 ? std::sqrt(before / after) : 0.0;
  for (int a = 0; a < 3; ++a) v[a] *= scale;
}

struct TangentialSpring {
  double stiffness = 0;  // k_t, N/m
  double damping = 0;    // gamma_t, N s/m
};

// Tangential force on particle i, F_t = F_s - gamma_t v_t with F_s += -k_t v_t dt (when
// `update`), capped at |F_t| <= mu |F_n|; at the cap the spring is reset to the elastic part of
// the capped force, F_s = F_t + gamma_t v_t, so that it slides (Coulomb) and, once the slip
// stops, holds. `spring` is the stored F_s (in the current tangent plane, see
// rotate_onto_tangent_plane); v_t the tangential velocity of i's contact point relative to
// the partner's. Without `update` the force is evaluated from the stored spring, unchanged.
inline void tangential_history_force(const TangentialSpring& k, double mu, double normal_force,
                                     const double vt[3], double dt, bool update,
                                     double spring[3], double f[3]) {
  double elastic[3];
  for (int a = 0; a < 3; ++a) {
    elastic[a] = update ? spring[a] - k.stiffness * vt[a] * dt : spring[a];
    f[a] = elastic[a] - k.damping * vt[a];
  }
  const double cap = mu * normal_force;
  const double squared = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];  // the root only at the cap
  if (squared > cap * cap) {
    const double scale = cap / std::sqrt(squared);
    for (int a = 0; a < 3; ++a) {
      f[a] *= scale;
      elastic[a] = f[a] + k.damping * vt[a];
    }
  }
  if (update) {
    for (int a = 0; a < 3; ++a) spring[a] = elastic[a];
  }
}

}  // namespace powderbed::dem
