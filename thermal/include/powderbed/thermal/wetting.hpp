#pragma once
// Molten particles wet what they touch (the consolidation Ganeriwala & Zohdi 2016 name as their
// model's main error). Liquid 316L (η ≈ 6e-3 Pa s, γ ≈ 1.8 N/m, ρ ≈ 7300 kg/m³: Mills,
// "Recommended values of thermophysical properties for selected commercial alloys", 2002) has
// an Ohnesorge number Oh = η / √(ρ γ r) ≈ 0.015 ≪ 1 for r = 13.5 µm, so it spreads in the
// inertial regime, on τ ≈ √(ρ r³ / γ) ≈ 3 µs (Eggers, Lister & Stone, J. Fluid Mech. 401:293,
// 1999; Biance, Clanet & Quéré, Phys. Rev. E 69:016301, 2004), shorter than the tens of
// microseconds a particle under the beam stays molten: the contact takes its end state at once.
// - where its melt remelts the solid under it (the contact temperature of the liquid particle
//   and the solid, contact_temperature.hpp, at or above T_m): a spherical cap of the
//   particle's volume V meeting the melt at the contact angle θ (Young's equilibrium); its base
//   is the contact area and the conduction length is the cap centroid's height above the base;
// - where that interface is below T_m: the liquid–solid interface freezes and the contact
//   line arrests on touch (splat solidification: Pasandideh-Fard et al., Int. J. Heat Mass
//   Transfer 41:2929, 1998); the particle meets the plate through an interfacial conductance
//   h_c (of order 1e5–1e6 W/m²K while the splat is liquid: Liu, Wang & Matthys, Int. J. Heat
//   Mass Transfer 38:1387, 1995) in series with the cap's conduction, until the interface
//   reaches T_m (the particle or the solid under it heats) and the cap spreads;
// - each top-face column is wetted once: a cap takes only the plate area earlier caps left;
// - with a molten neighbour: a liquid bridge whose neck has grown to the smaller sphere's
//   radius (coalescence drives the neck to the smaller drop's section before the pair merges).
// A wetted contact stays wetted after it freezes (the solid bridge remains).
#include <cmath>
#include <numbers>

namespace powderbed::thermal {

struct SpreadCap {
  double base_radius;      // a, m
  double centroid_height;  // height of the cap's centroid above its base, m
};

// Spherical cap of volume V and contact angle θ (radians, 0 < θ < π): V = π R³ f(θ) / 3 with
// f = 2 - 3 cos θ + cos³ θ, base radius R sin θ, height H = R (1 - cos θ); the centroid lies
// 3 (2R - H)² / (4 (3R - H)) above the sphere's centre, i.e. that minus (R - H) above the base.
inline SpreadCap spherical_cap(double volume, double contact_angle) {
  const double c = std::cos(contact_angle);
  const double f = 2 - 3 * c + c * c * c;
  const double big_r = std::cbrt(3 * volume / (std::numbers::pi * f));
  const double h = big_r * (1 - c);
  const double centroid = 3 * (2 * big_r - h) * (2 * big_r - h) / (4 * (3 * big_r - h)) - (big_r - h);
  return {big_r * std::sin(contact_angle), centroid};
}

// Neck radius of the liquid bridge between two molten spheres.
inline double bridge_radius(double r_i, double r_j) { return std::fmin(r_i, r_j); }

// Energy into body 1 over dt through a conductance G between two lumped capacities C1, C2 at
// temperatures T1, T2, integrated exactly: G (T2 - T1) dt (1 - e^{-x}) / x, x = G dt (1/C1 +
// 1/C2). It never overshoots the common temperature, whatever G: a wetted contact can be far
// stiffer than the grid step allows an explicit flux to be.
inline double exact_exchange(double conductance, double c1, double t1, double c2, double t2,
                             double dt) {
  const double x = conductance * dt * (1 / c1 + 1 / c2);
  const double phi = x > 1e-8 ? -std::expm1(-x) / x : 1 - 0.5 * x;
  return conductance * (t2 - t1) * dt * phi;
}

}  // namespace powderbed::thermal
