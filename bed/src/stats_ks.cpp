// Kolmogorov–Smirnov tests of a layer's sizes against its feed (docs/spread-layer.md "PSD"):
//   two samples: D = sup_x |F_a(x) - F_b(x)| over the empirical CDFs;
//   against a PSD: D = sup |F_n(x) - F(x)| (ks_distance);
//   p = Q_KS(lambda), lambda = (sqrt(n_e) + 0.12 + 0.11 / sqrt(n_e)) D, with n_e = n_a n_b /
//   (n_a + n_b) (two samples) or n (one): Stephens (1970) JRSS B 32:115, the form of Press et al.,
//   Numerical Recipes (3rd ed.) §14.3.3, accurate for n_e >= 4.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "powderbed/bed/stats_layer.hpp"

namespace powderbed::bed {

namespace {

double ks_p(double d, double effective_n) {
  if (!(effective_n > 0)) return 1.0;
  const double s = std::sqrt(effective_n);
  return kolmogorov_tail((s + 0.12 + 0.11 / s) * d);
}

}  // namespace

// Q_KS(lambda) = 2 sum_{k>=1} (-1)^(k-1) exp(-2 k^2 lambda^2); below lambda = 1.18 that series
// converges slowly and the Jacobi-transformed form 1 - sqrt(2 pi)/lambda sum_{k>=1}
// exp(-(2k-1)^2 pi^2 / (8 lambda^2)) is used (both to double precision in <= 5 terms there).
double kolmogorov_tail(double lambda) {
  if (!(lambda > 0)) return 1.0;
  constexpr double pi = std::numbers::pi;
  double q = 0;
  if (lambda < 1.18) {
    const double y = -pi * pi / (8.0 * lambda * lambda);
    double sum = 0;
    for (int k = 1; k <= 6; ++k) sum += std::exp((2 * k - 1) * (2 * k - 1) * y);
    q = 1.0 - std::sqrt(2.0 * pi) / lambda * sum;
  } else {
    double sign = 1;
    for (int k = 1; k <= 6; ++k, sign = -sign) q += 2.0 * sign * std::exp(-2.0 * k * k * lambda * lambda);
  }
  return std::clamp(q, 0.0, 1.0);
}

KsTest ks_two_sample(std::vector<double> a, std::vector<double> b) {
  KsTest t;
  t.n1 = a.size();
  t.n2 = b.size();
  if (a.empty() || b.empty()) return t;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    // Step both CDFs past the next value (ties in both samples step together).
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] == x) ++i;
    while (j < b.size() && b[j] == x) ++j;
    t.d = std::max(t.d, std::abs(static_cast<double>(i) / na - static_cast<double>(j) / nb));
  }
  t.p = ks_p(t.d, na * nb / (na + nb));
  return t;
}

KsTest ks_against_psd(const std::vector<double>& diameters, const Psd& psd) {
  KsTest t;
  t.n1 = diameters.size();
  if (diameters.empty()) return t;
  std::vector<double> radii(diameters.size());
  std::transform(diameters.begin(), diameters.end(), radii.begin(), [](double d) { return 0.5 * d; });
  t.d = ks_distance(std::move(radii), psd);
  t.p = ks_p(t.d, static_cast<double>(diameters.size()));
  return t;
}

}  // namespace powderbed::bed
