#pragma once
// Continuous sliding friction of docs/physics.md §4, regularised near zero slip.
#include <cmath>

namespace powderbed::dem {

struct SlidingFrictionParams {
  double coefficient = 0;  // mu_d
  // Slip speed below which the force fades out linearly (m/s). The direction of
  // F = -mu_d |F_n| t is undefined at v_t = 0; with t = v_t / sqrt(|v_t|^2 + v_reg^2) the
  // force is smooth there and acts as a viscous damper of rate mu_d |F_n| / v_reg, so a
  // particle at rest cannot chatter from one side to the other. 1e-5 m/s is well below
  // the impact speeds of a drop (0.1–1 m/s) and above the speed noise of a settled bed
  // (the rest threshold is 1e-4 m/s), so sliding is Coulomb and rest is quiet.
  double regularisation_speed = 1e-5;
};

// Friction force on particle i for a normal force magnitude `normal_force` and tangential
// relative velocity (vt_x, vt_y, vt_z) = tangential part of v_i - v_j:
// F = -mu_d |F_n| v_t / sqrt(|v_t|^2 + v_reg^2) (docs/physics.md §4). Writes the force into f.
inline void sliding_friction_force(const SlidingFrictionParams& p, double normal_force,
                                   double vt_x, double vt_y, double vt_z, double f[3]) {
  const double speed2 = vt_x * vt_x + vt_y * vt_y + vt_z * vt_z;
  const double scale = -p.coefficient * normal_force /
                       std::sqrt(speed2 + p.regularisation_speed * p.regularisation_speed);
  f[0] = scale * vt_x;
  f[1] = scale * vt_y;
  f[2] = scale * vt_z;
}

}  // namespace powderbed::dem
