#pragma once
// Conduction kernels of the effective-conductivity network (docs/physics.md §6): gas conductivity,
// Batchelor–O'Brien contact conductance and the Hertz correction of the contact radius for beds
// settled with a softened modulus. Each returns a conductance (W/K) or a length.
#include <cmath>

#include "powderbed/bed/contact_geometry.hpp"
#include "powderbed/bed/softening.hpp"
#include "powderbed/bed/option_words.hpp"

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
// (bed/softening.hpp turns the DEM's overlap into it, conducting_overlap below). For a wall
// R* = r (its radius is infinite).
inline double hertz_contact_radius(double reduced_radius, double hertz_overlap) {
  return hertz_overlap > 0 ? std::sqrt(reduced_radius * hertz_overlap) : 0.0;
}

// The normal law of the DEM run that made the bed (bed::ContactProvenance).
enum class BedContactLaw { hertz, linear };

// Which circle an overlap δ (the bed's, or the Hertz overlap the correction reads from it)
// conducts through:
// - hertz: the elastic contact circle a = √(R* δ) (Hertz 1882);
// - geometric: the circle where the two spheres intersect at centre distance r_i + r_j − δ,
//   a² = r_i² − x², x = (d² + r_i² − r_j²) / (2d); for small δ a² ≈ 2 R* δ, √2 times the Hertz
//   radius. This is what MFiX's DES conduction, which [KE] ran, takes (at its corrected
//   overlap). A wall is the limit r_j → ∞ of both: √(r δ) and √(2 r δ − δ²).
enum class ContactCircle { hertz, geometric };
inline constexpr bed::OptionWord<ContactCircle> kContactCircleWords[] = {
    {"hertz", ContactCircle::hertz}, {"geometric", ContactCircle::geometric}};

// How a contact radius is taken from the bed's geometry.
struct ContactRadiusParams {
  bool hertz_correction = false;  // false: the bed's own overlap; true: the equivalent Hertz one
  ContactCircle circle = ContactCircle::geometric;
  BedContactLaw law = BedContactLaw::hertz;
  // hertz: E*_true / E*_DEM, the bed's softening S (E' / E_bed times it when the correction
  // reads the packing at another modulus E', contact.young)
  double young_scale = 1;
  double stiffness = 0;       // linear: k_n of the DEM, N/m
  double pair_modulus = 0;    // linear: E* of two particles at the true moduli, Pa
  double wall_modulus = 0;    // linear: E* of a particle on a wall, Pa
};

// The overlap a contact conducts through: the bed's `overlap` of reduced radius R* (a wall:
// R* = r), or with the correction the Hertz overlap of the same force at the true moduli.
inline double conducting_overlap(const ContactRadiusParams& p, double reduced_radius,
                                 double overlap, bool wall) {
  if (overlap <= 0) return 0;
  if (!p.hertz_correction) return overlap;
  if (p.law == BedContactLaw::linear)
    return bed::hertz_overlap_of_linear(overlap, p.stiffness, wall ? p.wall_modulus : p.pair_modulus,
                                        reduced_radius);
  return bed::hertz_overlap_of_softened(overlap, p.young_scale);
}

// Particle–particle contact radius at centre distance d (0 when apart).
inline double pair_contact_radius(const ContactRadiusParams& p, double r_i, double r_j, double d) {
  const double reduced = r_i * r_j / (r_i + r_j);
  const double delta = conducting_overlap(p, reduced, r_i + r_j - d, false);
  if (p.circle == ContactCircle::hertz) return hertz_contact_radius(reduced, delta);
  return delta > 0 ? bed::contact_radius(r_i, r_j, r_i + r_j - delta) : 0.0;
}

// Particle–wall contact radius, the centre `h` from the wall plane: the pair's law at
// r_j → ∞ (R* = r; the plane cuts the sphere in a circle of radius √(r² − (r − δ)²)).
inline double wall_contact_radius(const ContactRadiusParams& p, double r, double h) {
  const double delta = conducting_overlap(p, r, r - h, true);
  if (p.circle == ContactCircle::hertz) return hertz_contact_radius(r, delta);
  return delta > 0 ? bed::plane_contact_radius(r, r - delta) : 0.0;
}

}  // namespace powderbed::keff
