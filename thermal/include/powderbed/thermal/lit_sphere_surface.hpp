#pragma once
// The lit surface of a lumped sphere: how much hotter than the particle's mean temperature the
// surface a beam heats is (docs/physics.md "Particles under the beam"). A lumped particle
// holds one temperature, right while its Biot number under the beam, q0 r / (k ΔT), is small;
// a 27 µm 316L particle in a 4e10 W/m² beam is far past that (q0 r / k ~ 5,000 K), so its lit
// surface, where it evaporates, runs thousands of kelvin above its mean.
//
// A parallel beam on a sphere of radius r deposits q(θ) = q0 cos θ on the lit hemisphere
// (absorbed power P = π r² q0). Two limits of conduction in the sphere (Carslaw & Jaeger 1959:
// ch. 2, the semi-infinite body under a constant flux; ch. 9, the sphere):
//   penetration, t ≲ 0.3 r²/κ: each point of the lit face heats as a semi-infinite body under
//     its flux, 2 q √(κ t / π) / k; averaged over the lit disc with weight cos θ (the flux's and
//     the evaporating area π r²'s), (4/3) q0 √(κ t / π) / k;
//   quasi-steady, t ≳ 0.3 r²/κ: the mean rises at P / (m c) and the deviation from it is the
//     steady solution of Laplace's equation for the flux's Legendre components a_l
//     (a_l = (2l + 1)/2 ∫₀¹ μ P_l(μ) dμ): ΔT(μ) = (q0 r / k) (a_0 / 5 + Σ_{l≥1} a_l P_l(μ) / l),
//     whose cos θ-weighted mean over the lit disc is kLitDiscExcess q0 r / k (0.69 at the pole).
// The excess is the smaller of the two (they cross at t ≈ 0.32 r²/κ): right in both limits, an
// interpolation between them (its error near the crossing is not estimated here).
#include <algorithm>
#include <cmath>
#include <numbers>

namespace powderbed::thermal {

// 2 ∫₀¹ μ ΔT(μ) dμ / (q0 r / k) of the quasi-steady series above (400 terms; the test sums it).
inline constexpr double kLitDiscExcess = 0.4236;

// Excess of the lit disc's mean surface temperature over the sphere's mean, K, for peak
// absorbed flux q0 (W/m²), radius r, conductivity k and diffusivity kappa, lit for t seconds.
inline double lit_surface_excess(double q0, double r, double k, double kappa, double t) {
  const double penetration = 4.0 / 3.0 * q0 * std::sqrt(kappa * t / std::numbers::pi) / k;
  return std::min(penetration, kLitDiscExcess * q0 * r / k);
}

// The lit surface's temperature when it also evaporates: the conduction excess is linear in the
// net flux into the sphere, so T_s = T + ΔT (1 - E(T_s) / P) with E the evaporation's power at
// T_s (latent heat, over the same disc), increasing in T_s: one root in [T, T + ΔT], found by
// bisection to 1e-3 K. `evaporation_power(T)` is E in W.
template <class Power>
double lit_surface_temperature(double t_mean, double excess, double absorbed, Power evaporation_power) {
  if (!(excess > 0) || !(absorbed > 0)) return t_mean;
  double lo = t_mean, hi = t_mean + excess;
  while (hi - lo > 1e-3) {
    const double mid = 0.5 * (lo + hi);
    const double balance = mid - t_mean - excess * (1 - evaporation_power(mid) / absorbed);
    (balance < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace powderbed::thermal
