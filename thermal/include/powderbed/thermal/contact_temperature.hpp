#pragma once
// Contact temperature of two bodies brought into sudden contact. Each is semi-infinite on the
// time scale that matters (the diffusion length √(κ t) short against its size) and perfectly
// conducting across the interface; the interface then sits at once, and stays, at
//   T_c = (e₁ T₁ + e₂ T₂) / (e₁ + e₂),   e = √(k ρ c), the thermal effusivity
// (Carslaw & Jaeger, "Conduction of Heat in Solids", 2nd ed. 1959, §2.15). Whether a liquid
// metal drop freezes on touch or melts its way into the solid it meets is read from T_c against
// the melting point (Gielen et al., "Solidification of liquid metal drops during impact",
// J. Fluid Mech. 883:A32, 2020, use this interface temperature for the onset of freezing): the
// wetting model spreads a molten particle where the interface under it is at or above T_m
// (wetting.hpp) and arrests it where the interface is colder.
#include <cmath>

namespace powderbed::thermal {

// e = √(k ρ c), J/(m² K s^½).
inline double effusivity(double conductivity, double density, double specific_heat) {
  return std::sqrt(conductivity * density * specific_heat);
}

// T_c of body 1 (effusivity e1, temperature t1) meeting body 2 (e2, t2).
inline double contact_temperature(double e1, double t1, double e2, double t2) {
  return (e1 * t1 + e2 * t2) / (e1 + e2);
}

}  // namespace powderbed::thermal
