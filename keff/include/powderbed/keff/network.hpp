#pragma once
// The heat-path network of a bed between two isothermal walls (docs/physics.md §6): one link per heat
// path and particle pair (or particle and wall). Conduction links carry G (T_j − T_i) with a
// constant conductance G (W/K); radiation links carry σ G_r (T_j⁴ − T_i⁴) with the grey-body
// exchange area G_r (m²) of docs/physics.md §6.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/contact_geometry.hpp"
#include "powderbed/keff/scene.hpp"

namespace powderbed::keff {

enum class HeatPath : std::uint8_t { contact, gas, radiation };

// `j` is a particle, or one of the walls below.
inline constexpr std::uint32_t kHotWall = std::numeric_limits<std::uint32_t>::max();
inline constexpr std::uint32_t kColdWall = kHotWall - 1;

struct KeffLink {
  std::uint32_t i, j;  // i: a node (particle or radiosity node); j: a node or a wall
  double conductance;  // > 0: W/K for contact and gas, the exchange area G_r (m²) for radiation
  HeatPath path;
};

struct KeffNetwork {
  // Nodes 0 … n−1 are the particles; the radiosity model adds its radiosity nodes after them
  // (node_count > n), whose "temperature" τ = (J/σ)^(1/4) makes every radiosity link a
  // radiation link σ G (τ_j⁴ − τ_i⁴).
  std::size_t node_count = 0;
  std::vector<KeffLink> links;
  double wall_area = 0;  // A_wall: the domain's cross-section normal to the axis, m²
  double height = 0;     // H: the distance between the walls, m
  std::size_t lost_rays = 0;  // view-factor rays still bouncing in the side mirrors at the cap
  // The view factors' Monte-Carlo error, measured by their reciprocity:
  // √(Σ_pairs (A_i F_ij − A_j F_ji)²) / √(Σ_pairs S_ij²), S_ij the pair's mean exchange area
  // (exactly 0 for exact F; shrinks as 1/√rays). 0 without radiation.
  double reciprocity_error = 0;
  // Gas links were built with k_g = gas_reference (W/mK). With gas_follows_temperature (the air
  // model) each carries G k_g(T̄) / gas_reference, T̄ the mean of its two ends' temperatures.
  double gas_reference = 0;
  bool gas_follows_temperature = false;
  // Radiation straight from wall to wall through the bed's gaps, G_r (m²): a link between the
  // two fixed walls, so it adds σ G_r (T_hot⁴ − T_cold⁴) to both wall flows.
  double wall_exchange = 0;
};

// Stefan–Boltzmann constant, W/(m² K⁴), shared with the laser solver.
using bed::kStefanBoltzmann;

// Links of every path the scene switches on; pairs come from the bed's cell list with a gap
// that covers the gas lenses; radiation links from Monte-Carlo view factors (radiation.hpp).
// Throws InputError for a 2D bed, an axis that is periodic, or a
// particle centre outside the walls (naming its id). `progress`, when set, hears the fraction of
// the view-factor tracing done (ViewFactorParams::progress).
KeffNetwork build_keff_network(const bed::Bed& bed, const KeffScene& scene,
                               const std::function<void(double)>& progress = {});

}  // namespace powderbed::keff
