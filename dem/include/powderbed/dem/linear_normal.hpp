#pragma once
// Linear spring–dashpot normal contact (Cundall & Strack 1979; the law of the MFiX-DEM beds of
// Kumar Yadav & Eshraghi [KE] 2016, k_n = 1e5 N/m): F = k_n delta + c delta',
// c = 2 zeta sqrt(m* k_n). Stateless kernels over a small parameter struct, as hertz_normal.hpp.
// Unlike the Hertz law it is not clamped: as in MFiX (calc_force_dem: F = -k_n delta n -
// eta_n v_n n), the dashpot may pull briefly before the overlap closes, which is what gives the
// closed forms below.
#include <cmath>
#include <numbers>

#include "powderbed/bed/critical_damping.hpp"

namespace powderbed::dem {

struct LinearNormalParams {
  double stiffness = 0;      // k_n, N/m
  double damping_ratio = 0;  // zeta: 0 elastic, 1 critical
};

// A pair's constants, taken out once per neighbour-list build: k_n and c = 2 zeta sqrt(m* k_n).
struct LinearPairConstants {
  double stiffness = 0;  // k_n, N/m
  double damping = 0;    // c, N s/m
};

inline LinearPairConstants linear_pair_constants(const LinearNormalParams& p,
                                                 double reduced_mass) {
  return {p.stiffness, bed::critical_damping(p.damping_ratio, reduced_mass, p.stiffness)};
}

// Elastic part F_e = k_n delta, delta > 0 the overlap.
inline double linear_elastic_force(const LinearPairConstants& c, double delta) {
  return c.stiffness * delta;
}

// F = k_n delta + c delta', delta' the approach rate (> 0 closing); negative (a pull) only
// while the overlap opens fast. The force on particle i is -F n with n from i to its partner.
inline double linear_damped_force(const LinearPairConstants& c, double delta,
                                  double approach_rate) {
  return c.stiffness * delta + c.damping * approach_rate;
}

// Elastic energy stored in the contact, 1/2 k_n delta^2.
inline double linear_elastic_energy(const LinearNormalParams& p, double delta) {
  return 0.5 * p.stiffness * delta * delta;
}

// Undamped angular frequency of a contact of reduced mass m*: omega_0 = sqrt(k_n / m*).
inline double linear_natural_frequency(const LinearNormalParams& p, double reduced_mass) {
  return std::sqrt(p.stiffness / reduced_mass);
}

// Contact duration pi / (omega_0 sqrt(1 - zeta^2)) (half a damped period; zeta < 1).
inline double linear_contact_time(const LinearNormalParams& p, double reduced_mass) {
  return std::numbers::pi /
         (linear_natural_frequency(p, reduced_mass) * std::sqrt(1.0 - p.damping_ratio * p.damping_ratio));
}

// Coefficient of restitution exp(-pi zeta / sqrt(1 - zeta^2)), independent of the impact speed
// and of m* (zeta < 1).
inline double linear_restitution(double damping_ratio) {
  return std::exp(-std::numbers::pi * damping_ratio /
                  std::sqrt(1.0 - damping_ratio * damping_ratio));
}

}  // namespace powderbed::dem
