#pragma once
// Stokes drag of a sphere in a quiescent fluid (docs/physics.md §4): F_env = -6 pi mu_f r v.
#include <numbers>

namespace powderbed::dem {

struct StokesDragParams {
  double viscosity = 0;  // mu_f, Pa s
};

// Drag coefficient 6 pi mu_f r (kg/s): the force is -coefficient * v.
inline double stokes_drag_coefficient(const StokesDragParams& p, double radius) {
  return 6.0 * std::numbers::pi * p.viscosity * radius;
}

// Terminal settling speed under gravity g (no buoyancy, as in docs/physics.md §4): 2 rho g r^2 / (9 mu_f).
inline double stokes_terminal_speed(const StokesDragParams& p, double density, double gravity,
                                    double radius) {
  return 2.0 * density * gravity * radius * radius / (9.0 * p.viscosity);
}

}  // namespace powderbed::dem
