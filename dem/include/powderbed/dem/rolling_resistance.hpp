#pragma once
// Rolling resistance, the elastic–plastic spring–dashpot model of Ai, Chen, Rotter & Ooi 2011
// (Powder Technol. 206, 269, "model type C"; LIGGGHTS's `rolling_friction epsd`, LAMMPS's
// `rolling sds`): a torque spring on the relative rolling rotation, M_k += -k_r omega_r dt,
// k_r = 2.25 mu_r^2 R*^2 k_n, capped at |M_k| <= mu_r R* |F_n|, plus a dashpot
// M_d = -C_r omega_r, C_r = 2 zeta sqrt(I_r k_r), while the spring is below its cap (Ai et al.:
// none once the resistance is fully mobilised). While a particle rolls the torque sits at the
// cap, the constant-torque law; when the rolling stops the spring holds it and the dashpot
// damps its rocking (a constant-torque law alone flips sign every step).
#include <cmath>

#include "powderbed/dem/tangential_history.hpp"

namespace powderbed::dem {

// k_r = 2.25 mu_r^2 R*^2 k_n (Ai et al. 2011, eq. 13, after Iwashita & Oda 1998), k_n the
// normal contact stiffness.
inline double rolling_stiffness(double mu_r, double reduced_radius, double normal_stiffness) {
  return 2.25 * mu_r * mu_r * reduced_radius * reduced_radius * normal_stiffness;
}

// The contact's moment of inertia for rolling (Ai et al. 2011, eq. 16):
// 1 / I_r = 1 / (I_i + m_i r_i^2) + 1 / (I_j + m_j r_j^2); a wall adds nothing (I_j infinite).
inline double rolling_inertia(double mass_i, double radius_i, double mass_j, double radius_j) {
  const double ii = 1.4 * mass_i * radius_i * radius_i;  // 2/5 m r^2 + m r^2
  const double ij = 1.4 * mass_j * radius_j * radius_j;
  return 1.0 / (1.0 / ii + 1.0 / ij);
}

struct RollingSpring {
  double stiffness = 0;  // k_r, N m / rad
  double damping = 0;    // C_r, N m s / rad
};

// Rolling torque on particle i (its partner gets -M_r). `torque` is the stored spring torque
// M_k, turned into the current tangent plane; omega_rel = omega_i - omega_j, whose normal part
// (twist) does not roll. Without `update` the stored spring is used unchanged.
inline void rolling_resistance_torque(const RollingSpring& k, double mu_r, double reduced_radius,
                                      double normal_force, const double n[3],
                                      const double omega_rel[3], double dt, bool update,
                                      double torque[3], double out[3]) {
  rotate_onto_tangent_plane(torque, n);
  const double twist = omega_rel[0] * n[0] + omega_rel[1] * n[1] + omega_rel[2] * n[2];
  double roll[3], m[3];
  for (int a = 0; a < 3; ++a) {
    roll[a] = omega_rel[a] - twist * n[a];
    m[a] = update ? torque[a] - k.stiffness * roll[a] * dt : torque[a];
  }
  const double cap = mu_r * reduced_radius * normal_force;
  const double squared = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];  // the root only at the cap
  const bool full = squared > cap * cap;
  const double scale = full ? cap / std::sqrt(squared) : 1.0;
  for (int a = 0; a < 3; ++a) {
    m[a] *= scale;
    if (update) torque[a] = m[a];
    out[a] = full ? m[a] : m[a] - k.damping * roll[a];
  }
}

}  // namespace powderbed::dem
