#pragma once
// Particle conduction through contacts (docs/physics.md §5): Q = K (T_j - T_i) A_ij / |x_j - x_i|,
// A_ij = π a^2 with a the radius of the circle in which two overlapping spheres intersect.
#include <cmath>

#include "powderbed/bed/contact_geometry.hpp"

namespace powderbed::thermal {

// The intersection circles of two spheres and of a sphere and a plane, shared with keff.
using bed::contact_radius;
using bed::plane_contact_radius;

// Geometric factor A/L of a conduction path: multiply by the conductivity for W/K.
inline double conduction_shape_factor(double contact_radius, double length) {
  return M_PI * contact_radius * contact_radius / length;
}

}  // namespace powderbed::thermal
