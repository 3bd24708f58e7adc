#include "powderbed/dem/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/dem/contact_moduli.hpp"
#include "powderbed/dem/fines_scaling.hpp"
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

namespace {

// The contact and drag steps of one particle of radius r whose inertial mass and Young's
// modulus carry the fines factors (fines_scaling.hpp; 1 and 1 without scaling).
struct ParticleSteps {
  double contact = INFINITY, drag = INFINITY;  // s
};

ParticleSteps particle_steps(const Scene& scene, const ContactModuli& moduli, double r) {
  const Material& m = scene.material;
  const double mass_factor = fines_mass_factor(scene.fines, r);
  const double stiffness_factor = fines_stiffness_factor(scene.fines, r);
  const double density = m.density * mass_factor;
  const double mass = bed::sphere_volume(r) * density;
  ParticleSteps steps;
  if ((scene.has(kHertz) || scene.has(kWalls)) && scene.law == ContactLaw::linear) {
    // The stiffest contact is a pair of two such particles (m* = m/2), or the particle on a
    // wall (m* = m) when pairs are off; 1/omega_0 = t_c sqrt(1 - zeta^2) / pi.
    const LinearNormalParams spring{scene.stiffness, m.damping};
    steps.contact = linear_stable_time_step(spring, scene.has(kHertz) ? mass / 2 : mass);
  } else if (scene.has(kHertz) || scene.has(kWalls)) {
    steps.contact = rayleigh_time_step(r, density, moduli.young * stiffness_factor, m.poisson);
    if (scene.has(kWalls)) {
      // A softer wall gives a longer contact; a stiffer one does not shorten the particle's own
      // Rayleigh step below that of the pair E* of two particles of the stiffer material. A
      // stiffness-scaled fine takes the wall's E scaled alike: even on a rigid wall its
      // E*/m* = E_i / ((1 - nu^2) m_i) is that of a pair of two such fines (E_i/(2(1 - nu^2)), m_i/2).
      const double stiffer = std::max(moduli.young, moduli.wall_young) * stiffness_factor;
      steps.contact = std::min(steps.contact, rayleigh_time_step(r, density, stiffer, m.poisson));
    }
  }
  // Drag acts on the particle's own radius; its relaxation is slowed by the scaled mass.
  if (scene.has(kDrag)) steps.drag = mass / stokes_drag_coefficient({scene.fluid_viscosity}, r);
  return steps;
}

}  // namespace

TimeStepBound time_step_bound(const bed::Bed& bed, const Scene& scene, double young_scale) {
  if (!(young_scale > 0) || !std::isfinite(young_scale)) {
    throw InputError(
        fmt::format("--young-scale: {:g} is out of range (accepted: S > 0)", young_scale));
  }
  if (bed.n() == 0) throw InputError("deposit: the bed has no particles (accepted: N >= 1)");
  const ContactModuli moduli = contact_moduli(scene, young_scale);
  const char* contact = scene.law == ContactLaw::linear ? "contact" : "rayleigh";
  TimeStepBound bound;
  bound.stable = INFINITY;
  // Every particle's own steps (with fines scaling the smallest particle need not be the one
  // that limits); the first particle of the shortest step names the limit.
  for (const double r : bed.radius) {
    const ParticleSteps steps = particle_steps(scene, moduli, r);
    if (steps.contact < bound.stable) {
      bound.stable = steps.contact;
      bound.limited_by = contact;
      bound.limiting_radius = r;
    }
    if (steps.drag < bound.stable) {
      bound.stable = steps.drag;
      bound.limited_by = "drag";
      bound.limiting_radius = r;
    }
  }
  bound.recommended = kTimeStepSafety * bound.stable;
  return bound;
}

}  // namespace powderbed::dem
