#pragma once
// Evaporation of a hot metal surface (docs/physics.md "Evaporation").
// Saturation pressure by Clausius–Clapeyron from the boiling point T_b at ambient pressure p0:
//   p_sat(T) = p0 exp(L_v M / R (1/T_b − 1/T)),
// net mass flux by Hertz–Knudsen–Langmuir with back-condensation β_r:
//   ṁ = (1 − β_r) p_sat(T) √(M / (2π R T))         (kg/m²s),
// the energy it carries off, L_v ṁ per unit area, and the recoil pressure on the melt,
//   p_r ≈ 0.54 p_sat(T).
// β_r = 0.18 and the factor 0.54 are Anisimov's (Sov. Phys. JETP 27:182, 1968) Knudsen-layer
// solution for strong evaporation, p_sat ≫ p0 (Knight, AIAA J. 17:519, 1979, the same
// analysis with a background gas): about 18 % of the emitted atoms return to the surface. Near
// and below T_b, where p_sat ~ p0, Knight's back-condensation rises toward 1 and the recoil
// toward p0, so a fixed β_r = 0.18 overstates the flux there: the loss is an upper bound
// (docs/physics.md "Evaporation").
#include <cmath>
#include <numbers>

namespace powderbed::thermal {

inline constexpr double kGasConstant = 8.314462618;  // R, J/mol K

struct EvaporationParams {
  double boiling_point;     // T_b at p0, K
  double latent_vapour;     // L_v, J/kg
  double molar_mass;        // M, kg/mol
  double ambient_pressure;  // p0, Pa
  double back_condensation; // β_r
};

inline double saturation_pressure(const EvaporationParams& p, double t) {
  return p.ambient_pressure *
         std::exp(p.latent_vapour * p.molar_mass / kGasConstant * (1 / p.boiling_point - 1 / t));
}

// Net evaporated mass flux at surface temperature t, kg/m²s.
inline double evaporation_mass_flux(const EvaporationParams& p, double t) {
  return (1 - p.back_condensation) * saturation_pressure(p, t) *
         std::sqrt(p.molar_mass / (2 * std::numbers::pi * kGasConstant * t));
}

// Recoil pressure on the surface at temperature t, Pa (Anisimov 1968).
inline double recoil_pressure(const EvaporationParams& p, double t) {
  return 0.54 * saturation_pressure(p, t);
}

}  // namespace powderbed::thermal
