#pragma once
// Geometry and constants the laser solver (thermal) and the effective conductivity (keff) both
// use, defined once: the circle where two spheres or a sphere and a plane intersect, a sphere's
// area, the Stefan–Boltzmann constant.
#include <cmath>
#include <numbers>

namespace powderbed::bed {

// Stefan–Boltzmann constant, W/m^2K^4 (CODATA 2018, exact in the SI).
inline constexpr double kStefanBoltzmann = 5.670374419e-8;

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

// Surface area 4 pi r^2 of a sphere of radius r.
inline double sphere_area(double r) { return 4 * std::numbers::pi * r * r; }

}  // namespace powderbed::bed
