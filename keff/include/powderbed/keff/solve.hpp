#pragma once
// Steady state of the heat-path network between the walls and the effective conductivity
// k_eff = (Q_wall / A_wall) · H / (T_hot − T_cold) (docs/physics.md §6). Contact and constant-k_g gas
// links are linear (one conjugate-gradient solve); radiation links (T⁴) and gas links that follow
// temperature make it nonlinear, solved by Newton with the analytic Jacobian (solve.cpp).
#include <cstdint>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/keff/network.hpp"

namespace powderbed::keff {

struct KeffResult {
  double k_eff = 0;           // W/mK, from the mean of the two wall flows
  double heat_flow_hot = 0;   // W, out of the hot wall into the bed
  double heat_flow_cold = 0;  // W, out of the bed into the cold wall
  // Share of each path in the heat carried across the bed: by Tellegen's theorem
  // Σ_links G ΔT² = Q_wall (T_hot − T_cold), so each path's part of that sum is its share.
  double share_contact = 0, share_gas = 0, share_radiation = 0;
  // Particles with no heat path to either wall (rattlers and floating clusters): left out of the
  // solve, their temperature set to the mean wall temperature (they have no steady state).
  std::vector<std::uint32_t> rattlers;  // particle indices, ascending
  std::vector<double> temperature;      // K, one per particle
  std::size_t links = 0, contact_links = 0, gas_links = 0, radiation_links = 0;
  // Newton steps: 1 for a linear network (one step from any start); with radiation or gas that
  // follows temperature, the steps after the linearised start to scene.newton_tolerance.
  std::size_t newton_iterations = 0;
  std::size_t solver_iterations = 0;  // inner iterations (CG, then BiCGSTAB), all steps together
  double residual = 0;  // final ‖R‖ / ‖Σ|q|‖ over the particles (0 for the linear network)
  std::size_t lost_rays = 0;  // view-factor rays still bouncing in the side mirrors at the cap
};

// Throws InputError when no particle has a heat path to a wall (naming the wall), and
// NumericalError if the linear solve does not converge.
KeffResult solve_keff(const bed::Bed& bed, const KeffScene& scene);
KeffResult solve_keff(const bed::Bed& bed, const KeffScene& scene, const KeffNetwork& network);

}  // namespace powderbed::keff
