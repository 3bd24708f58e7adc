#pragma once
// Moving Gaussian laser with Beer–Lambert penetration (docs/physics.md §5):
//   I(r, z) = I0 exp(-beta z) exp(-2 r^2 / w^2),  I0 = 2 P / (π w^2),
// absorbed power of a particle H_i = alpha I A_i with A_i = π r_i^2; beta from Gusarov:
//   beta = 3 (1 - gamma) / (2 gamma D), gamma the porosity, D the mean diameter.
#include <cmath>

namespace powderbed::thermal {

struct LaserParams {
  double power;         // P, W
  double spot_radius;   // w, m (1/e^2 radius)
  double absorptivity;  // alpha
  double extinction;    // beta, 1/m
};

// Squared distance from the axis in spot radii squared beyond which the beam is below 1e-16
// of its peak (exp(-2 x 18.5) = 8.5e-17): the solver cuts it there.
constexpr double kBeamCutoff2 = 18.5;

inline double peak_intensity(const LaserParams& p) {
  return 2 * p.power / (M_PI * p.spot_radius * p.spot_radius);
}

// The beam's profile I / I0 = exp(-2 r^2 / w^2) at horizontal distance^2 `r2` from its axis,
// `w2` = w^2.
inline double gaussian_profile(double r2, double w2) { return std::exp(-2 * r2 / w2); }

// The share exp(-beta z) of the beam that passes `depth` z of powder of extinction `beta`.
inline double beer_lambert_transmission(double beta, double depth) {
  return std::exp(-beta * depth);
}

// Absorbed flux alpha I (W/m^2) at horizontal distance^2 `r2` from the beam axis, `depth` below
// the bed's top surface.
inline double absorbed_flux(const LaserParams& p, double r2, double depth) {
  return p.absorptivity * peak_intensity(p) * beer_lambert_transmission(p.extinction, depth) *
         gaussian_profile(r2, p.spot_radius * p.spot_radius);
}

// The part of H_i that is fixed for a fixed bed: alpha A_i exp(-beta z_i), W per W/m^2 of peak
// intensity, for a particle of projected area `area` A_i at `depth` z_i.
inline double particle_laser_factor(double absorptivity, double area, double beta, double depth) {
  return absorptivity * area * beer_lambert_transmission(beta, depth);
}

// H_i of a particle at horizontal distance^2 `r2` from the axis: its particle_laser_factor
// times I0 exp(-2 r^2 / w^2).
inline double particle_laser_power(double laser_factor, double peak, double r2, double w2) {
  return laser_factor * peak * gaussian_profile(r2, w2);
}

// Power onto a top node of the substrate: alpha I(r, 0) times the fraction `transmission` of
// the beam that passes the powder above it, over the node's face dx dy.
inline double node_laser_power(const LaserParams& p, double r2, double transmission, double dx,
                               double dy) {
  return absorbed_flux(p, r2, 0.0) * transmission * dx * dy;
}

inline double gusarov_extinction(double porosity, double mean_diameter) {
  return 3 * (1 - porosity) / (2 * porosity * mean_diameter);
}

}  // namespace powderbed::thermal
