#pragma once
// Particle conduction through contacts (docs/physics.md §5): Q = K (T_j - T_i) A_ij / |x_j - x_i|,
// A_ij = π a^2 with a the radius of the circle in which two overlapping spheres intersect, and
// K the mean of the two sides' conductivities; the substrate grid's faces conduct by the same law.
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

// Conductance G = K A/L (W/K) of a path of shape factor `shape` = A/L between two bodies of
// conductivities k_i and k_j: K is their arithmetic mean (docs/physics.md §5).
inline double path_conductance(double k_i, double k_j, double shape) {
  return 0.5 * (k_i + k_j) * shape;
}

// Heat flow Q = G (T_j - T_i) (W) into body i from body j, `delta_t` = T_j - T_i. With
// k_i = k_j = K it is K shape delta_t to the last bit: 0.5 (K + K) is K exactly.
inline double conduction_flow(double k_i, double k_j, double shape, double delta_t) {
  return path_conductance(k_i, k_j, shape) * delta_t;
}

}  // namespace powderbed::thermal
