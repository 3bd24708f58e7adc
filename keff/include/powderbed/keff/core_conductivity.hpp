#pragma once
// The bed's own conductivity away from the walls, and how much of the temperature drop the
// walls take (docs/keff.md, "What a run reports"):
//   k_core = q / |dT/dx|_core,
// q = Q / A_wall the heat flux between the walls (the mean of the two wall flows), dT/dx the
// slope of the least-squares line T(x) through the particles whose centres lie more than
// `margin` (two mean diameters) from both walls. This is the quantity of [KE] (Kumar Yadav &
// Eshraghi 2016): fixed temperatures at two opposite walls, the flux over the gradient of the
// bin-averaged profile, which they found approximately linear. Where the profile is a straight
// line from wall to wall, k_core equals the wall-to-wall k_eff = q H / (T_hot − T_cold); a wall
// that touches the bed badly shows as a jump between the wall temperature and the core line
// extrapolated to the wall, reported as a share of T_hot − T_cold.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "powderbed/bed/bed.hpp"

namespace powderbed::keff {

struct CoreConductivity {
  double k_core = 0;          // W/mK; NaN when fewer than two particles lie in the core
  double gradient = 0;        // dT/dx of the core line, K/m (positive: the hot wall is upper)
  double margin = 0;          // m: the core starts this far from each wall
  std::size_t particles = 0;  // in the core (rattlers left out)
  // T_hot − T_line(upper face) and T_line(lower face) − T_cold over T_hot − T_cold: the share
  // of the drop lost between each wall and the core (0 for a straight line wall to wall).
  double drop_hot = 0, drop_cold = 0;
};

// `flux` = Q / A_wall (W/m²); particles listed in `excluded` (ascending: the rattlers) are left
// out; `margin` < 0 takes two mean diameters.
CoreConductivity core_conductivity(const bed::Bed& bed, int axis,
                                   const std::vector<double>& temperature,
                                   const std::vector<std::uint32_t>& excluded, double flux,
                                   double t_hot, double t_cold, double margin = -1);

}  // namespace powderbed::keff
