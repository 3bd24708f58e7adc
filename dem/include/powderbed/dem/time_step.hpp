#pragma once
// Stable time step of a deposition (docs/physics.md §4, docs/architecture.md "Numerical stability").
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/linear_normal.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::dem {

// Rayleigh time step t_R = pi r sqrt(rho / G) / (0.1631 nu + 0.8766), G = E / (2 (1 + nu))
// (docs/physics.md §4).
double rayleigh_time_step(double radius, double density, double young, double poisson);

// Stable bound of the linear spring–dashpot law (linear_normal.hpp) for a contact of reduced
// mass m*: 1 / omega_0 = sqrt(m* / k_n), i.e. the contact time pi / (omega_0 sqrt(1 - zeta^2))
// times sqrt(1 - zeta^2) / pi. At omega_0 dt = 1, half of velocity Verlet's limit of 2, as the
// Rayleigh step is for a Hertz pair at 1 % overlap (below); the default 0.2 of it resolves a
// contact in pi / 0.2 ~ 16 steps.
double linear_stable_time_step(const LinearNormalParams& p, double reduced_mass);

// The default step is this fraction of the stable bound. The Rayleigh step is near the
// explicit limit: at t_R a Hertz pair of equal spheres overlapped by 1 % of a radius has
// omega dt ~ 1 (velocity Verlet diverges at omega dt = 2, RK4 at 2.83), so 0.2 keeps about
// 30 steps per contact oscillation, enough for the contact time within 1 %.
constexpr double kTimeStepSafety = 0.2;

struct TimeStepBound {
  double stable = 0;       // largest accepted --dt (without --unsafe-dt), s
  double recommended = 0;  // kTimeStepSafety * stable, the default, s
  // "rayleigh" (Hertz contact), "contact" (linear contact, 1/omega_0), "drag" (Stokes
  // relaxation), "none"
  const char* limited_by = "none";
  double limiting_radius = 0;  // m, the radius of the particle whose step is the bound
};

// Bound over the bed's particles (the smallest one without fines scaling; with it, each
// particle's own step with its scaled mass or modulus, fines_scaling.hpp) with E / young_scale
// for particle and wall: min over the effects that are on of t_R (hertz or walls; the wall's E when it is softer;
// with the linear law linear_stable_time_step instead)
// and the Stokes relaxation time m / (6 pi mu_f r) (drag; velocity Verlet on a linear drag is
// stable below twice that). Both are +inf when no effect bounds the step (hertz, walls and
// drag off: then dt must be given). Throws InputError for an empty bed or young_scale <= 0.
TimeStepBound time_step_bound(const bed::Bed& bed, const Scene& scene, double young_scale);

}  // namespace powderbed::dem
