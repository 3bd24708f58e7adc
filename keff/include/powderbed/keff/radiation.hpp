#pragma once
// Grey-body radiation links of the effective-conductivity network (docs/physics.md §6), from the view
// factors of view_factors.hpp. S_ij = A_i F_ij is the exchange area, A = 4π r². Monte-Carlo
// F break reciprocity by their sampling error, so a pair's S is the mean of A_i F_ij and A_j F_ji:
// one link per pair, and the heat flows are antisymmetric (the wall flows then agree). Rays that
// return to their own sphere through a side mirror carry no net heat and make no link. The walls
// exchange with each other through the bed's gaps with S = A_wall F_wall.
//
// Two models (scene.radiation_model):
// - pair (docs/physics.md §6): Q_ij = σ (T_i⁴ − T_j⁴) G_r with
//   1 / G_r = (1−ε_i)/(ε_i A_i) + 1/S_ij + (1−ε_j)/(ε_j A_j). A wall is a grey plane far larger
//   than a particle, of which only the patch facing the particle exchanges with it: its surface
//   resistance is taken over the particle's own area, (1−ε_w)/(ε_w A_i). Each link carries the
//   whole surface resistance of both spheres, though a sphere exchanges with ~10 neighbours at
//   once: the surface term is then small against 1/S_ij (F_ij ≈ 0.1), so ε barely matters.
// - radiosity (the grey diffuse enclosure, Oppenheim's network): each surface k gets a radiosity
//   node J_k joined to its blackbody node σT_k⁴ by the surface conductance ε_k A_k/(1−ε_k), and
//   radiosity nodes are joined by the space conductances S_kl. The surface resistance is then
//   shared by all of a surface's links, as it physically is. Each wall is one radiosity node
//   (uniform radiosity over the wall). Written with τ = (J/σ)^(1/4) every link is a radiation
//   link σ G (τ_l⁴ − τ_k⁴), so the Newton solve needs nothing new; a black surface (ε = 1) needs
//   no radiosity node. With all surfaces black both models are the same network.
#include "powderbed/bed/bed.hpp"
#include "powderbed/keff/network.hpp"
#include "powderbed/keff/view_factors.hpp"

namespace powderbed::keff {

// G_r (m²) of two grey surfaces of emissivities ε and areas A with exchange area S = A_i F_ij.
inline double grey_exchange_area(double eps_i, double area_i, double exchange, double eps_j,
                                 double area_j) {
  return 1 / ((1 - eps_i) / (eps_i * area_i) + 1 / exchange + (1 - eps_j) / (eps_j * area_j));
}

// Adds the radiation links of view factors `vf` of `bed` to `net` (with the radiosity model, its
// radiosity nodes after net.node_count), and sets net.wall_exchange or the wall-to-wall link.
void add_radiation_links(const bed::Bed& bed, const KeffScene& scene, const ViewFactors& vf,
                         KeffNetwork& net);

}  // namespace powderbed::keff
