#pragma once
// Fresnel absorptance of a metal surface (Born & Wolf, "Principles of Optics", §14.2): light of
// vacuum wavelength λ meets a medium of complex refractive index N = n + i k at angle θ from
// the normal. With c = cos θ and the complex square root s = √(N² − sin² θ),
//   r_s = (c − s) / (c + s),   r_p = (N² c − s) / (N² c + s),
//   A(θ) = 1 − (|r_s|² + |r_p|²) / 2        (unpolarised light: s and p averaged).
// At normal incidence A(0) = 4n / ((n + 1)² + k²); at grazing incidence A → 0. For 316L near
// 1.06 µm, N ≈ 3.2 + 4.3i gives A(0) ≈ 0.35, and A averaged over a sphere's projected disc
// (θ from 0 to 90°, weighted by the disc's area 2 cos θ sin θ dθ) ≈ 0.37: the first hit on a
// powder particle absorbs a little more than a flat plate (A rises to 0.42 near 77°, the
// principal angle, before it falls to 0).
#include <cmath>
#include <complex>

namespace powderbed::thermal {

// A(θ) for cos θ = `cos_incidence` in [0, 1] (values outside are clamped).
inline double fresnel_absorptance(std::complex<double> index, double cos_incidence) {
  const double c = std::fmin(1.0, std::fmax(0.0, cos_incidence));
  const std::complex<double> n2 = index * index;
  const std::complex<double> s = std::sqrt(n2 - (1 - c * c));
  const double rs = std::norm((c - s) / (c + s));
  const double rp = std::norm((n2 * c - s) / (n2 * c + s));
  return 1 - 0.5 * (rs + rp);
}

}  // namespace powderbed::thermal
