#pragma once
// What a DEM run's contact law leaves in a bed, read at the materials' true stiffness
// (docs/physics.md §4 and §6). A run softened by S (--young-scale) had its contacts E / S stiff,
// or its law was a linear spring k_n; the overlaps it left are then too deep. Whoever reads the
// bed at the true moduli (keff's contact radius, deposit's full-stiffness overlap) takes the
// overlap the true Hertz contact would have under the same force.
#include <cmath>

namespace powderbed::bed {

// The modulus the softened run used: E / S.
inline double softened_modulus(double young, double young_scale) { return young / young_scale; }

// Hertz at E* / S and at E* under one force, (4/3)(E*/S) sqrt(R*) delta_s^{3/2} =
// (4/3) E* sqrt(R*) delta_h^{3/2}: delta_h = delta_s S^{-2/3}.
inline double hertz_overlap_of_softened(double soft_overlap, double young_scale) {
  return soft_overlap * std::pow(young_scale, -2.0 / 3.0);
}

// A linear spring and Hertz under one force, k_n delta_s = (4/3) E* sqrt(R*) delta_h^{3/2}:
// delta_h = (3 k_n delta_s / (4 E* sqrt(R*)))^{2/3} (the equivalence Kumar Yadav & Eshraghi 2016
// use for their MFiX-DEM beds). For a wall R* = r and E* is the particle–wall modulus.
inline double hertz_overlap_of_linear(double overlap, double stiffness, double effective_modulus,
                                      double reduced_radius) {
  return std::cbrt(std::pow(3 * stiffness * overlap / (4 * effective_modulus * std::sqrt(reduced_radius)), 2));
}

}  // namespace powderbed::bed
