#pragma once
// `sinter --explain` (docs/architecture.md "Effects a scene calls for"): the scale analysis of [GZ]
// (docs/physics.md §5) for this scene and bed — each heat path's flux relative to the absorbed laser
// flux alpha I0 while a particle heats towards melting, the lumped-capacitance Biot numbers —
// and which effects matter (ratio >= 1e-3) or could be switched off. A heat path is called
// negligible only when it is so for the whole run: under the beam (its flux over the laser's)
// and in the cooling after the beam has passed, up to the run's end (the heat it carries off a
// lit particle over that time, per the heat the particle holds at T_m).
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/solver.hpp"

namespace powderbed::thermal {

struct ExplainReport {
  double laser_flux = 0;            // alpha I0, W/m^2
  double conduction_scale = 0;      // [GZ]'s estimate k (T_m - T0) / D / (alpha I0): full contact
  double conduction_ratio = 0;      // particle–particle contacts, mean over connected particles
  double substrate_ratio = 0;       // particle–substrate contacts
  double convection_ratio = 0;      // h (T_v - T_env) / (alpha I0)
  double radiation_ratio = 0;       // eps sigma (T_v^4 - T_env^4) / (alpha I0)
  double biot_surface = 0;          // (h + 4 eps sigma T_v^3) (r/3) / k
  double biot_laser = 0;            // alpha I0 (r/3) / (k (T_m - T0))
  double optical_thickness = 0;     // beta H_layer
  double dwell_time = 0;            // w / v, s
  double heating_time = 0;          // m c (T_m - T0) / (alpha I0 pi r^2), mean particle, s
  double absorptance = 0;           // the laser model's, beam at the bed's centre
  double wetting_time = 0;          // m c / (k π a^2 / z_c) of a mean particle's spread cap, s
  // The regime (King et al., J. Mater. Process. Technol. 214:2915, 2014): ΔH/h_s =
  // A P / (π h_s √(D v w³)), h_s = ρ c T_m, D = k/(ρ c) of the solid at (T0 + T_m)/2, w the
  // beam's 1/e² radius, A the flat surface's absorptance; keyhole beyond π T_b / T_m.
  double normalised_enthalpy = 0, keyhole_threshold = 0;
  double evaporation_ratio = 0;     // L_v ṁ(T_b) / (alpha I0): evaporation at the boiling point
  // The cooling after the beam: t_cool = t_end - w/v, the longest a lit particle (one lit at the
  // run's start) cools before the run ends, s; and over it, per the heat m c (T_m - T0) a mean
  // particle holds at T_m, what each path carries off (linearised: t_cool / tau, tau = m c / G
  // the path's time constant; contacts: G = k Σ A/L, losses: the flux at T_b over π r²).
  double cooling_time = 0;
  double conduction_cooling = 0, substrate_cooling = 0;
  double convection_cooling = 0, radiation_cooling = 0;
  // Whether lit particles melt with wetting on: their pairs then cool through liquid bridges
  // (wetting.hpp) whose necks have the smaller sphere's radius, and conduction_cooling is that
  // of such a neck when it is the larger.
  bool bridged = false;
  std::string text;                 // the printed report
};

ExplainReport explain(const bed::Bed& bed, const SinterScene& scene, const Sinter& sinter);

// The regime of King et al. 2014 alone (ExplainReport::normalised_enthalpy, keyhole_threshold):
// ΔH/h_s of the scene's power, speed and spot on material `m`, and π T_b / T_m.
struct KingRegime {
  double normalised_enthalpy = 0, keyhole_threshold = 0;
};
KingRegime king_regime(const SinterScene& scene, const Material& m);

}  // namespace powderbed::thermal
