#pragma once
// The dashpot of a damped spring: c = 2 zeta sqrt(m k), zeta the damping ratio (0 elastic, 1
// critical, c_c = 2 sqrt(m k)) of a spring of stiffness k on a mass m (docs/physics.md §4:
// c = 2 zeta sqrt(m* k_n)). The DEM's normal, tangential and rolling dashpots (m the reduced
// mass m* or the rolling inertia I_r, k the matching stiffness) and the decks that hand them to
// LAMMPS and LIGGGHTS take it here; it lives in bed/ because the decks cannot reach dem/.
#include <cmath>

namespace powderbed::bed {

inline double critical_damping(double damping_ratio, double mass, double stiffness) {
  return 2.0 * damping_ratio * std::sqrt(mass * stiffness);
}

}  // namespace powderbed::bed
