#pragma once
// Particle–fluid–particle conduction of Rong & Horio (docs/physics.md §6): each particle carries a gas
// lens of thickness `lens` r; heat crosses the gas where the lenses overlap, through the gap
// l(ρ) between the two surfaces at distance ρ from the centre line:
//   Q / ΔT = k_g ∫ 2π ρ / max(l_min, l(ρ)) dρ   over the lens-overlap circle.
// The functions below return the geometric factor (m) of that integral; multiply by k_g.
//
// Choices (docs/keff.md): the integral runs outside the solid contact circle only (inside it the
// path is solid and contact conduction carries it); a wall carries no lens of its own. The outer
// edge of the region is where the two lenses intersect (the wording of docs/physics.md §6), capped at the smaller
// sphere's radius where the gap is still defined, or, as MFiX's DES_CONDUCTION computes it for
// [KE], where the larger particle's lens meets the smaller particle's surface.
//
// Quadrature: with u = ρ² the integral is π ∫ du / max(l_min, l(u)). The part where l < l_min is
// exact, π Δu / l_min. On the rest the substitution w = ln l turns it into π ∫ (du/dl) dw, whose
// integrand du/dl is smooth and slowly varying (≈ 2R* near contact, where the original integrand
// peaks like 1/l), so fixed Gauss–Legendre converges geometrically; kGasLensNodes points reach
// round-off against a 2e6-point midpoint reference (tests/keff/test_gas.cpp).
#include "powderbed/bed/option_words.hpp"

namespace powderbed::keff {

inline constexpr int kGasLensNodes = 32;

enum class LensRegion {
  both_lenses,  // out to the circle where the two lenses intersect
  larger_lens,  // out to where the larger particle's lens meets the smaller particle (MFiX)
};
inline constexpr bed::OptionWord<LensRegion> kLensRegionWords[] = {
    {"both-lenses", LensRegion::both_lenses}, {"larger-lens", LensRegion::larger_lens}};

struct GasLensParams {
  double lens = 0.2;       // lens thickness over the particle radius
  double min_gap = 1e-6;   // l_min, m: bounds the integrand at contact
  LensRegion region = LensRegion::both_lenses;
};

// Factor of the pair (i, j) at centre distance d; 0 when the lenses do not overlap.
double gas_pair_factor(const GasLensParams& p, double r_i, double r_j, double d);
// Factor of a particle whose centre is `h` from a wall plane.
double gas_wall_factor(const GasLensParams& p, double r, double h);

}  // namespace powderbed::keff
