#pragma once
// Scaling of the fines (docs/physics.md §4 "Fines"): the Rayleigh step t_R = pi r sqrt(rho / G) /
// (0.1631 nu + 0.8766) grows as r sqrt(rho / E), so the smallest particle of a wide PSD sets
// the step of the whole bed. A particle of radius r below the reference radius R_ref (m) gets
// the factor
//     s = (R_ref / r)^2   (r < R_ref),   s = 1   (r >= R_ref),
// and either its inertial mass is multiplied by s (mass scaling: rho s, the density scaling
// of quasi-static DEM, Thornton 2000, Geotechnique 50(1) 43-53) or its Young's modulus divided
// by s (stiffness scaling: E / s); with either, r sqrt(rho / E) and so t_R are those of a
// particle of radius R_ref. The same two remedies hold an explicit finite-element step at a
// target (Altair Radioss /DT/NODA: nodal mass added, CST, or nodal stiffness reduced, SET).
#include "powderbed/dem/scene.hpp"

namespace powderbed::dem {

// s = (R_ref / r)^2 below R_ref, 1 at and above it (radius, reference_radius in m).
inline double fines_factor(double radius, double reference_radius) {
  if (!(radius < reference_radius)) return 1.0;
  const double ratio = reference_radius / radius;
  return ratio * ratio;
}

// The factor on the particle's inertial mass: s under mass scaling, else 1.
inline double fines_mass_factor(const Fines& fines, double radius) {
  return fines.scaling == FinesScaling::mass ? fines_factor(radius, fines.radius) : 1.0;
}

// The factor on the particle's Young's modulus: 1 / s under stiffness scaling, else 1.
inline double fines_stiffness_factor(const Fines& fines, double radius) {
  return fines.scaling == FinesScaling::stiffness ? 1.0 / fines_factor(radius, fines.radius) : 1.0;
}

}  // namespace powderbed::dem
