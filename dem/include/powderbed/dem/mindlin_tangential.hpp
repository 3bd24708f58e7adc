#pragma once
// Mindlin's tangential stiffness of a Hertz contact (Mindlin 1949, J. Appl. Mech. 16, 259;
// docs/deposit-spread.md "Static friction"): k_t = 8 G* sqrt(R* delta), G* the pair's effective
// shear modulus. The spring it sets is tangential_history.hpp's; LAMMPS's `tangential mindlin`
// takes the same 8 G*. Stateless kernels, as hertz_normal.hpp.
#include <cmath>

namespace powderbed::dem {

// An isotropic material's shear modulus G = E / (2 (1 + nu)).
inline double shear_modulus(double young, double poisson) { return young / (2.0 * (1.0 + poisson)); }

// G* of a pair, 1 / G* = (2 - nu_i) / G_i + (2 - nu_j) / G_j.
inline double effective_shear_modulus(double young_i, double poisson_i, double young_j,
                                      double poisson_j) {
  return 1.0 / ((2.0 - poisson_i) / shear_modulus(young_i, poisson_i) +
                (2.0 - poisson_j) / shear_modulus(young_j, poisson_j));
}

// k_t = 8 G* sqrt(R* delta), delta > 0 the overlap.
inline double mindlin_stiffness(double effective_shear, double reduced_radius, double delta) {
  return 8.0 * effective_shear * std::sqrt(reduced_radius * delta);
}

// The pair's constant, taken out once per neighbour-list build (as hertz_pair_constants):
// k_t = s delta^{1/2} with s = 8 G* sqrt(R*).
inline double mindlin_stiffness_constant(double effective_shear, double reduced_radius) {
  return 8.0 * effective_shear * std::sqrt(reduced_radius);
}

}  // namespace powderbed::dem
