#pragma once
// The vapour depression (docs/physics.md "The vapour depression"): the melt surface is pushed
// down where the recoil pressure beats the capillary pressure that holds it flat,
//   0.54 p_sat(T) > 2 γ / w     (γ the liquid's surface tension, w the beam radius: the
//                                depression's radius of curvature is of the beam's size),
// the hydrostatic ρ g d being 1e-4 of it at these depths. The model is the isotherm cavity of
// keyhole-welding models (Kaplan, J. Phys. D 27:1805, 1994; Lankalapalli, Tu & Gartner, J. Phys.
// D 29:1831, 1996): the cavity is the region hotter than the temperature T_d at which the two
// pressures balance; the melt it held is displaced, and the beam goes on to the cavity's wall.
// The cavity's surface is the T_d isotherm on each column of the substrate grid; rays are
// traced into it and reflect on its walls (multiple reflections raise the absorptance), and the
// power a column's surface absorbs goes into the column's topmost node below T_d (the beam
// drills as fast as the wall heats). Not modelled: the melt flow around the cavity, its
// dynamic collapse and the pores that leaves; the vapour plume's absorption.
#include <cmath>

#include "powderbed/thermal/evaporation.hpp"

namespace powderbed::thermal {

// T_d: the temperature at which the recoil pressure equals 2 γ / w (Clausius–Clapeyron solved
// for T), K.
inline double depression_temperature(const EvaporationParams& p, double surface_tension,
                                     double spot_radius) {
  const double capillary = 2 * surface_tension / spot_radius;
  const double ratio = capillary / (0.54 * p.ambient_pressure);
  return 1 / (1 / p.boiling_point - kGasConstant / (p.latent_vapour * p.molar_mass) * std::log(ratio));
}

// Depth below the top face of the isotherm T_d on one column, m: the column's node
// temperatures from the top (t[0] at the top face, spacing dz), interpolated linearly between
// the last node at or above T_d and the first below it; 0 if the top node is below T_d.
template <class Temperature>
double isotherm_depth(Temperature t, std::size_t nodes, double dz, double t_d) {
  if (t(0) < t_d) return 0;
  for (std::size_t k = 1; k < nodes; ++k) {
    const double above = t(k - 1), below = t(k);
    if (below < t_d) return dz * (static_cast<double>(k - 1) + (above - t_d) / (above - below));
  }
  return dz * static_cast<double>(nodes - 1);
}

}  // namespace powderbed::thermal
