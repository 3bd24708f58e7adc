#pragma once
// Hertz normal contact with the zeta viscous damping of docs/physics.md §4 (after LAMMPS's
// gran_normal_hertz_force): stateless kernels over a small parameter struct.
#include <cmath>

#include "powderbed/bed/critical_damping.hpp"

namespace powderbed::dem {

// E* of a material pair (docs/physics.md §4): 1 / ((1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j).
inline double effective_modulus(double young_i, double poisson_i, double young_j,
                                double poisson_j) {
  return 1.0 / ((1.0 - poisson_i * poisson_i) / young_i + (1.0 - poisson_j * poisson_j) / young_j);
}

struct HertzNormalParams {
  double effective_modulus = 0;  // E*, Pa
  double damping_ratio = 0;      // zeta: 0 elastic, 1 critical
};

// Elastic part F_e = 4/3 E* sqrt(R*) delta^{3/2} (docs/physics.md §4), delta > 0 the overlap.
inline double hertz_elastic_force(const HertzNormalParams& p, double reduced_radius, double delta) {
  return (4.0 / 3.0) * p.effective_modulus * std::sqrt(reduced_radius * delta) * delta;
}

// Contact stiffness k_n = dF_e/d delta = 2 E* sqrt(R* delta) (docs/physics.md §4).
inline double hertz_stiffness(const HertzNormalParams& p, double reduced_radius, double delta) {
  return 2.0 * p.effective_modulus * std::sqrt(reduced_radius * delta);
}

// Damped normal force magnitude F_e + c delta', c = 2 zeta sqrt(m* k_n), delta' the approach
// rate (> 0 closing), clamped at 0 so the contact never pulls (docs/physics.md §4). The force on particle
// i is -F n with n pointing from i to its partner.
inline double hertz_damped_force(const HertzNormalParams& p, double reduced_radius,
                                 double reduced_mass, double delta, double approach_rate) {
  const double root = std::sqrt(reduced_radius * delta);
  const double elastic = (4.0 / 3.0) * p.effective_modulus * root * delta;
  const double stiffness = 2.0 * p.effective_modulus * root;
  const double force =
      elastic + bed::critical_damping(p.damping_ratio, reduced_mass, stiffness) * approach_rate;
  return force > 0.0 ? force : 0.0;
}

// The same law with the pair's constants taken out once (per neighbour-list build), so a step
// needs no division: F_e = a delta^{3/2} with a = 4/3 E* sqrt(R*), and c delta' =
// 2 zeta sqrt(m* 2 E* sqrt(R* delta)) delta' = b delta^{1/4} delta' with
// b = 2 zeta sqrt(2 E* m* sqrt(R*)) (docs/physics.md §4).
struct HertzPairConstants {
  double elastic = 0;  // a, N m^{-3/2}
  double damping = 0;  // b, N s m^{-5/4}
};

inline HertzPairConstants hertz_pair_constants(const HertzNormalParams& p, double reduced_radius,
                                               double reduced_mass) {
  const double root_r = std::sqrt(reduced_radius);
  return {(4.0 / 3.0) * p.effective_modulus * root_r,
          bed::critical_damping(p.damping_ratio, reduced_mass, 2.0 * p.effective_modulus * root_r)};
}

// F_e = a delta^{3/2}.
inline double hertz_elastic_force(const HertzPairConstants& c, double delta) {
  return c.elastic * std::sqrt(delta) * delta;
}

// F_e + c delta' = a delta^{3/2} + b delta^{1/4} delta', clamped at 0 (never pulls).
inline double hertz_damped_force(const HertzPairConstants& c, double delta, double approach_rate) {
  const double root = std::sqrt(delta);
  const double force = c.elastic * root * delta + c.damping * std::sqrt(root) * approach_rate;
  return force > 0.0 ? force : 0.0;
}

// Elastic energy stored in the contact, the integral of F_e: 8/15 E* sqrt(R*) delta^{5/2}.
inline double hertz_elastic_energy(const HertzNormalParams& p, double reduced_radius,
                                   double delta) {
  return (8.0 / 15.0) * p.effective_modulus * std::sqrt(reduced_radius * delta) * delta * delta;
}

}  // namespace powderbed::dem
