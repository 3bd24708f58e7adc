#pragma once
// Box walls and floor (docs/physics.md §4): the Hertz law of hertz_normal.hpp with the wall as a
// sphere of infinite radius and mass, so R* = r_i and m* = m_i, and E* from the pair
// (particle material, wall material).
#include "powderbed/dem/hertz_normal.hpp"

namespace powderbed::dem {

// Normal force magnitude (>= 0) pushing a particle of radius r, mass m away from a plane wall
// at overlap delta = r - (distance of the centre to the wall) > 0, approach rate delta'
// (> 0 when moving into the wall).
inline double wall_damped_force(const HertzNormalParams& p, double radius, double mass,
                                double delta, double approach_rate) {
  return hertz_damped_force(p, radius, mass, delta, approach_rate);
}

inline double wall_elastic_force(const HertzNormalParams& p, double radius, double delta) {
  return hertz_elastic_force(p, radius, delta);
}

}  // namespace powderbed::dem
