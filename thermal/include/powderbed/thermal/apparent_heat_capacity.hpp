#pragma once
// Apparent heat capacity of melting and vaporisation over a window ΔT (docs/physics.md §5):
//   c = c_s                       T < T_m - ΔT/2
//       (c_s + c_l)/2 + L_m/ΔT    |T - T_m| <= ΔT/2
//       c_l                       between the windows
//       (c_l + c_g)/2 + L_v/ΔT    |T - T_v| <= ΔT/2
//       c_g                       T > T_v + ΔT/2
// Integrated across a window it absorbs exactly L + (c_a + c_b)/2 ΔT per kg.
namespace powderbed::thermal {

struct ApparentHeatCapacityParams {
  double melting_point;   // T_m, K
  double boiling_point;   // T_v, K
  double window;          // ΔT, K
  double latent_melt;     // L_m, J/kg
  double latent_vapour;   // L_v, J/kg
};

inline double apparent_heat_capacity(double t, double c_solid, double c_liquid, double c_gas,
                                     const ApparentHeatCapacityParams& p) {
  const double half = 0.5 * p.window;
  if (t < p.melting_point - half) return c_solid;
  if (t <= p.melting_point + half) return 0.5 * (c_solid + c_liquid) + p.latent_melt / p.window;
  if (t < p.boiling_point - half) return c_liquid;
  if (t <= p.boiling_point + half) return 0.5 * (c_liquid + c_gas) + p.latent_vapour / p.window;
  return c_gas;
}

}  // namespace powderbed::thermal
