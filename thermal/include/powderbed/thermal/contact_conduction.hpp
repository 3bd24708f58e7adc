#pragma once
// Particle conduction through contacts (SPEC.md §5): Q = K (T_j - T_i) A_ij / |x_j - x_i|,
// A_ij = π a^2 with a the radius of the circle in which two overlapping spheres intersect.
#include <cmath>

namespace powderbed::thermal {

// Radius of the intersection circle of spheres r_i, r_j at centre distance d (law of cosines);
// 0 when they do not overlap, the smaller radius when one contains the other's centre plane.
inline double contact_radius(double r_i, double r_j, double d) {
  if (d >= r_i + r_j) return 0;
  if (d <= std::abs(r_i - r_j)) return std::fmin(r_i, r_j);
  const double x = (d * d + r_i * r_i - r_j * r_j) / (2 * d);  // from i's centre to the plane
  return std::sqrt(std::fmax(r_i * r_i - x * x, 0.0));
}

// Radius of the circle where a sphere whose centre is `h` above a plane cuts it (0 if h >= r).
inline double plane_contact_radius(double r, double h) {
  return h >= r ? 0 : std::sqrt(r * r - h * h);
}

// Geometric factor A/L of a conduction path: multiply by the conductivity for W/K.
inline double conduction_shape_factor(double contact_radius, double length) {
  return M_PI * contact_radius * contact_radius / length;
}

}  // namespace powderbed::thermal
