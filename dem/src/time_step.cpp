#include "powderbed/dem/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/contact_moduli.hpp"
#include "powderbed/dem/linear_normal.hpp"
#include "powderbed/dem/stokes_drag.hpp"

namespace powderbed::dem {

// docs/physics.md §4: t_R = pi r sqrt(rho / G) / (0.1631 nu + 0.8766), G = E / (2 (1 + nu)).
double rayleigh_time_step(double radius, double density, double young, double poisson) {
  return std::numbers::pi * radius * std::sqrt(density / shear_modulus(young, poisson)) / (0.1631 * poisson + 0.8766);
}

double linear_stable_time_step(const LinearNormalParams& p, double reduced_mass) {
  return 1.0 / linear_natural_frequency(p, reduced_mass);
}

TimeStepBound time_step_bound(const bed::Bed& bed, const Scene& scene, double young_scale) {
  if (!(young_scale > 0) || !std::isfinite(young_scale)) {
    throw InputError(
        fmt::format("--young-scale: {:g} is out of range (accepted: S > 0)", young_scale));
  }
  if (bed.n() == 0) throw InputError("deposit: the bed has no particles (accepted: N >= 1)");
  const double r_min = *std::min_element(bed.radius.begin(), bed.radius.end());
  TimeStepBound bound;
  bound.stable = INFINITY;
  if ((scene.has(kHertz) || scene.has(kWalls)) && scene.law == ContactLaw::linear) {
    // The stiffest contact is a pair of the smallest particles (m* = m/2), or that particle on
    // a wall (m* = m) when pairs are off; 1/omega_0 = t_c sqrt(1 - zeta^2) / pi.
    const double mass =
        4.0 / 3.0 * std::numbers::pi * r_min * r_min * r_min * scene.material.density;
    const LinearNormalParams spring{scene.stiffness, scene.material.damping};
    bound.stable = linear_stable_time_step(spring, scene.has(kHertz) ? mass / 2 : mass);
    bound.limited_by = "contact";
  } else if (scene.has(kHertz) || scene.has(kWalls)) {
    const Material& m = scene.material;
    const ContactModuli moduli = contact_moduli(scene, young_scale);
    double t = rayleigh_time_step(r_min, m.density, moduli.young, m.poisson);
    if (scene.has(kWalls)) {
      // A softer wall gives a longer contact; a stiffer one does not shorten the particle's own
      // Rayleigh step below that of the pair E* of two particles of the stiffer material.
      t = std::min(t, rayleigh_time_step(r_min, m.density, std::max(moduli.young, moduli.wall_young),
                                         m.poisson));
    }
    bound.stable = t;
    bound.limited_by = "rayleigh";
  }
  if (scene.has(kDrag)) {
    const double mass = 4.0 / 3.0 * std::numbers::pi * r_min * r_min * r_min * scene.material.density;
    const double relax = mass / stokes_drag_coefficient({scene.fluid_viscosity}, r_min);
    if (relax < bound.stable) {
      bound.stable = relax;
      bound.limited_by = "drag";
    }
  }
  bound.recommended = kTimeStepSafety * bound.stable;
  return bound;
}

}  // namespace powderbed::dem
