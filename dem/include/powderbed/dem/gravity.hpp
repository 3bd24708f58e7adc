#pragma once
// Gravity of docs/physics.md §4: F_grav = -m g z-hat (z is up in every bed).

namespace powderbed::dem {

struct GravityParams {
  double acceleration = 9.81;  // g, m/s^2
};

// Vertical force on a particle of mass m.
inline double gravity_force_z(const GravityParams& p, double mass) { return -mass * p.acceleration; }

}  // namespace powderbed::dem
