#pragma once
// Conduction kernels of the effective-conductivity network (docs/physics.md §6): gas conductivity,
// Batchelor–O'Brien contact conductance and the Hertz correction of the contact radius for beds
// settled with a softened modulus. Each returns a conductance (W/K) or a length.
#include <cmath>

#include "powderbed/bed/contact_geometry.hpp"

namespace powderbed::keff {

// Air conductivity of [KE] (docs/physics.md §6), W/mK, fitted over 175–1900 K.
inline double air_conductivity(double t) {
  return ((6.566e-12 * t - 3.386e-8) * t + 9.426e-5) * t + 7.505e-4;
}
// Its derivative dk_g/dT, W/(m K²): the Newton Jacobian of gas links that follow temperature.
inline double air_conductivity_slope(double t) {
  return (3 * 6.566e-12 * t - 2 * 3.386e-8) * t + 9.426e-5;
}

// Batchelor–O'Brien contact conductance Q / ΔT = 2 k_s a (docs/physics.md §6), with the calibration
// factor A_c scaling the contact radius a.
inline double contact_conductance(double solid_conductivity, double calibration, double radius) {
  return 2 * solid_conductivity * calibration * radius;
}

// A bed settled with Hertz contacts at E / S (S = young_scale, the DEM's softening) has overlaps
// δ_s too large. Equating the soft force (4/3)(E*/S)√R* δ_s^{3/2} with the true Hertz force
// (4/3) E* √R* δ_h^{3/2} (docs/physics.md §6) gives δ_h = δ_s S^{-2/3}, and the Hertz contact radius is
// a = √(R* δ_h). For a wall R* = r (the wall's radius is infinite).
inline double hertz_contact_radius(double reduced_radius, double soft_overlap, double young_scale) {
  if (soft_overlap <= 0) return 0;
  return std::sqrt(reduced_radius * soft_overlap * std::pow(young_scale, -2.0 / 3.0));
}

// A bed settled with a linear spring k_n (the MFiX-DEM beds of [KE]) has overlaps δ_s set by
// k_n, not by the material. Equating k_n δ_s with the Hertz force (4/3) E* √R* δ_h^{3/2}
// (Kumar Yadav & Eshraghi 2016, docs/physics.md §6) gives δ_h = (3 k_n δ_s / (4 E* √R*))^{2/3}, and
// a = √(R* δ_h). For a wall R* = r and E* is the particle–wall modulus.
inline double linear_spring_contact_radius(double reduced_radius, double soft_overlap,
                                           double stiffness, double effective_modulus) {
  if (soft_overlap <= 0) return 0;
  const double hertz_overlap = std::cbrt(std::pow(
      3 * stiffness * soft_overlap / (4 * effective_modulus * std::sqrt(reduced_radius)), 2));
  return std::sqrt(reduced_radius * hertz_overlap);
}

// The normal law of the DEM run that made the bed (bed::ContactProvenance).
enum class BedContactLaw { hertz, linear };

// How a contact radius is taken from the bed's geometry.
struct ContactRadiusParams {
  bool hertz_correction = false;  // false: the geometric circle where the spheres intersect
  BedContactLaw law = BedContactLaw::hertz;
  // hertz: E*_true / E*_DEM, the bed's softening S (E' / E_bed times it when the correction
  // reads the packing at another modulus E', contact.young)
  double young_scale = 1;
  double stiffness = 0;       // linear: k_n of the DEM, N/m
  double pair_modulus = 0;    // linear: E* of two particles at the true moduli, Pa
  double wall_modulus = 0;    // linear: E* of a particle on a wall, Pa
};

// Particle–particle contact radius at centre distance d (0 when apart).
inline double pair_contact_radius(const ContactRadiusParams& p, double r_i, double r_j, double d) {
  if (!p.hertz_correction) return bed::contact_radius(r_i, r_j, d);
  const double reduced = r_i * r_j / (r_i + r_j), overlap = r_i + r_j - d;
  if (p.law == BedContactLaw::linear)
    return linear_spring_contact_radius(reduced, overlap, p.stiffness, p.pair_modulus);
  return hertz_contact_radius(reduced, overlap, p.young_scale);
}

// Particle–wall contact radius, the centre `h` from the wall plane: a = √(r² − h²) geometric.
inline double wall_contact_radius(const ContactRadiusParams& p, double r, double h) {
  if (!p.hertz_correction) return bed::plane_contact_radius(r, h);
  if (p.law == BedContactLaw::linear)
    return linear_spring_contact_radius(r, r - h, p.stiffness, p.wall_modulus);
  return hertz_contact_radius(r, r - h, p.young_scale);
}

}  // namespace powderbed::keff
