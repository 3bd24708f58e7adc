#pragma once
// How much of the light a rough surface reflects goes on specularly (Bennett & Porteus, J. Opt.
// Soc. Am. 51:123, 1961, at normal incidence; Beckmann & Spizzichino, "The Scattering of
// Electromagnetic Waves from Rough Surfaces", 1963, at oblique incidence): for a surface whose
// heights are Gaussian with rms σ, light of wavelength λ at angle θ from the normal keeps the
// specular share
//   S = exp(−(4π σ cos θ / λ)²)
// of what it reflects; the rest is scattered. The ray tracer sends the scattered part out by
// Lambert's law (a surface with σ ≫ λ and slopes of tens of degrees, as machined or built
// metal, scatters close to it). For a 1.07 µm fibre laser a ground plate (σ ≈ 1 µm) reflects
// diffusely at every angle but the most grazing (S = 1/2 at cos θ ≈ 0.07); a polished one
// (σ = 0.02 µm) is a mirror (S = 0.94 at normal incidence).
#include <cmath>
#include <numbers>

namespace powderbed::thermal {

// S for rms height `rms_roughness` and `wavelength` (m) at cos θ = `cos_incidence`.
inline double specular_share(double rms_roughness, double wavelength, double cos_incidence) {
  const double g = 4 * std::numbers::pi * rms_roughness * cos_incidence / wavelength;
  return std::exp(-g * g);
}

}  // namespace powderbed::thermal
