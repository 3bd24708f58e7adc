#pragma once
// Conduction kernels of the effective-conductivity network (docs/physics.md §6): gas conductivity,
// Batchelor–O'Brien contact conductance and the Hertz correction of the contact radius for beds
// settled with a softened modulus. Each returns a conductance (W/K) or a length.
#include <cmath>

#include "powderbed/bed/contact_geometry.hpp"
#include "powderbed/bed/softening.hpp"

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

// The Hertz contact radius a = sqrt(R* delta_h) of an overlap delta_h at the true moduli
// (bed/softening.hpp turns the DEM's overlap into it). For a wall R* = r (its radius is
// infinite).
inline double hertz_contact_radius(double reduced_radius, double hertz_overlap) {
  return hertz_overlap > 0 ? std::sqrt(reduced_radius * hertz_overlap) : 0.0;
}

// A bed settled with Hertz contacts at E / S (S = young_scale, the DEM's softening).
inline double softened_contact_radius(double reduced_radius, double soft_overlap, double young_scale) {
  if (soft_overlap <= 0) return 0;
  return hertz_contact_radius(reduced_radius, bed::hertz_overlap_of_softened(soft_overlap, young_scale));
}

// A bed settled with a linear spring k_n (the MFiX-DEM beds of [KE]); E* the true modulus of the
// pair or of the particle on the wall.
inline double linear_spring_contact_radius(double reduced_radius, double soft_overlap,
                                           double stiffness, double effective_modulus) {
  if (soft_overlap <= 0) return 0;
  return hertz_contact_radius(
      reduced_radius, bed::hertz_overlap_of_linear(soft_overlap, stiffness, effective_modulus, reduced_radius));
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
  return softened_contact_radius(reduced, overlap, p.young_scale);
}

// Particle–wall contact radius, the centre `h` from the wall plane: a = √(r² − h²) geometric.
inline double wall_contact_radius(const ContactRadiusParams& p, double r, double h) {
  if (!p.hertz_correction) return bed::plane_contact_radius(r, h);
  if (p.law == BedContactLaw::linear)
    return linear_spring_contact_radius(r, r - h, p.stiffness, p.wall_modulus);
  return softened_contact_radius(r, r - h, p.young_scale);
}

}  // namespace powderbed::keff
