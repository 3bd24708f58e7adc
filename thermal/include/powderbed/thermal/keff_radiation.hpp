#pragma once
// Grey-body radiation links of the effective-conductivity network (SPEC.md §6):
//   Q_ij = σ (T_i⁴ − T_j⁴) G_r,  1 / G_r = (1−ε_i)/(ε_i A_i) + 1/S_ij + (1−ε_j)/(ε_j A_j),
// A = 4π r² and S_ij = A_i F_ij the exchange area of the view factors. Monte-Carlo F break
// reciprocity by their sampling error, so S_ij is the mean of A_i F_ij and A_j F_ji: one link
// per pair, and the heat flows are antisymmetric (the wall flows then agree).
//
// A wall is a grey plane of emissivity ε_w. It is far larger than a particle, but only the patch
// that faces the particle exchanges with it, so its surface resistance is taken over the
// particle's own area: (1−ε_w)/(ε_w A_i) (a black sphere facing a grey wall with F = 1 then
// behaves as two parallel grey surfaces of equal area). S_iw = A_i F_iw needs no symmetrising.
// Rays that return to their own sphere through a side mirror carry no net heat and make no link.
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/keff_network.hpp"
#include "powderbed/thermal/keff_view_factors.hpp"

namespace powderbed::thermal {

// G_r (m²) of two grey surfaces of emissivities ε and areas A with exchange area S = A_i F_ij.
inline double grey_exchange_area(double eps_i, double area_i, double exchange, double eps_j,
                                 double area_j) {
  return 1 / ((1 - eps_i) / (eps_i * area_i) + 1 / exchange + (1 - eps_j) / (eps_j * area_j));
}

// The radiation links (path radiation, conductance G_r) of view factors `vf` of `bed`, with the
// scene's emissivities.
std::vector<KeffLink> radiation_links(const bed::Bed& bed, const KeffScene& scene,
                                      const ViewFactors& vf);

}  // namespace powderbed::thermal
