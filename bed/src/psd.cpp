// Sampling, CDF and analytic moments of the particle size distributions of docs/physics.md §1.
// Parsing of the PSD string is in psd_parse.cpp.
#include "powderbed/bed/psd.hpp"

#include <algorithm>
#include <array>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

namespace {

constexpr double inv_sqrt2 = 0.70710678118654752440;
constexpr double sqrt2 = 1.41421356237309504880;
constexpr double inv_sqrt_2pi = 0.39894228040143267794;

// Standard normal CDF Phi, upper tail Q = 1 - Phi and density phi; erfc keeps both tails
// accurate down to the smallest doubles (and gives 0/1 at -+infinity).
double normal_cdf(double x) { return 0.5 * std::erfc(-x * inv_sqrt2); }
double normal_upper(double x) { return 0.5 * std::erfc(x * inv_sqrt2); }
double normal_pdf(double x) { return std::isinf(x) ? 0.0 : inv_sqrt_2pi * std::exp(-0.5 * x * x); }

// Phi(hi) - Phi(lo) without cancellation: upper-tail form when the window is above the centre.
double normal_mass(double lo, double hi) {
  if (lo >= 0) return normal_upper(lo) - normal_upper(hi);
  if (hi <= 0) return normal_cdf(hi) - normal_cdf(lo);
  return 1.0 - normal_cdf(lo) - normal_upper(hi);
}

// Phi^-1(p) and Q^-1(q) for p, q in [0, 0.5]; the end point 0 maps to -+infinity (erfc_inv
// would throw there).
double normal_lower_quantile(double p) {
  return p <= 0 ? -std::numeric_limits<double>::infinity() : -sqrt2 * boost::math::erfc_inv(2 * p);
}
double normal_upper_quantile(double q) {
  return q <= 0 ? std::numeric_limits<double>::infinity() : sqrt2 * boost::math::erfc_inv(2 * q);
}

// docs/physics.md §1: inverse CDF of the standard normal truncated to [lo, hi] at u in [0, 1). Works on
// whichever tail the quantile lies in, so a window far in a tail (e.g. [6, 7]) keeps full
// relative precision instead of collapsing to Phi = 1.
double truncated_normal_quantile(double lo, double hi, double u) {
  double y = 0;
  if (lo >= 0) {
    y = normal_upper_quantile(normal_upper(lo) - u * normal_mass(lo, hi));
  } else if (hi <= 0) {
    y = normal_lower_quantile(normal_cdf(lo) + u * normal_mass(lo, hi));
  } else {
    const double mass = normal_mass(lo, hi);
    const double p = normal_cdf(lo) + u * mass;
    y = p <= 0.5 ? normal_lower_quantile(p)
                 : normal_upper_quantile(normal_upper(hi) + (1 - u) * mass);
  }
  return std::clamp(y, lo, hi);
}

// E[Y^j], j = 0..3, of the standard normal truncated to [lo, hi], by the recursion
// m_j = (j-1) m_{j-2} + (lo^{j-1} phi(lo) - hi^{j-1} phi(hi)) / Z  (Z = window mass).
std::array<double, 4> truncated_normal_moments(double lo, double hi) {
  const double z = normal_mass(lo, hi);
  const double plo = normal_pdf(lo);
  const double phi = normal_pdf(hi);
  // x^k phi(x) -> 0 at infinity; written out so that inf * 0 never appears.
  auto term = [](double x, double pdf, int power) {
    return pdf == 0 ? 0.0 : std::pow(x, power) * pdf;
  };
  std::array<double, 4> m{};
  m[0] = 1;
  m[1] = (plo - phi) / z;
  m[2] = 1 + (term(lo, plo, 1) - term(hi, phi, 1)) / z;
  m[3] = 2 * m[1] + (term(lo, plo, 2) - term(hi, phi, 2)) / z;
  return m;
}

// Radius per unit of the component's size variable.
double radius_scale(const PsdComponent& c) { return c.on == SizeVariable::diameter ? 0.5 : 1.0; }

// Standardised window of gauss (in x) and lognormal (in ln x).
std::array<double, 2> gauss_window(const PsdComponent& c) {
  return {(c.min - c.mean) / c.sd, (c.max - c.mean) / c.sd};
}
std::array<double, 2> lognormal_window(const PsdComponent& c) {
  return {(std::log(c.min) - c.mu) / c.sigma, (std::log(c.max) - c.mu) / c.sigma};
}

bool is_point(const PsdComponent& c) {
  return c.kind == PsdComponent::Kind::mono || (c.kind == PsdComponent::Kind::gauss && c.sd == 0);
}

// P(X <= x) (or P(X < x) when `left`, which differs only at the atom of a point mass), X the
// component's size variable.
double cdf_variable(const PsdComponent& c, double x, bool left) {
  if (is_point(c)) return (left ? x > c.mean : x >= c.mean) ? 1.0 : 0.0;
  switch (c.kind) {
    case PsdComponent::Kind::gauss: {
      if (x <= c.min) return 0;
      if (x >= c.max) return 1;
      const auto [lo, hi] = gauss_window(c);
      return normal_mass(lo, (x - c.mean) / c.sd) / normal_mass(lo, hi);
    }
    case PsdComponent::Kind::lognormal: {
      if (x <= c.min) return 0;
      if (x >= c.max) return 1;
      const auto [lo, hi] = lognormal_window(c);
      return normal_mass(lo, (std::log(x) - c.mu) / c.sigma) / normal_mass(lo, hi);
    }
    case PsdComponent::Kind::table: {
      double below = 0;
      for (std::size_t i = 0; i + 1 < c.edges.size(); ++i) {
        if (x >= c.edges[i + 1]) {
          below += c.fractions[i];
        } else {
          if (x > c.edges[i]) {
            below += c.fractions[i] * (x - c.edges[i]) / (c.edges[i + 1] - c.edges[i]);
          }
          break;
        }
      }
      return std::min(below, 1.0);
    }
    case PsdComponent::Kind::mono:
      break;
  }
  return 0;
}

// E[X^k] of the component's size variable, k = 1..3.
double moment_variable(const PsdComponent& c, int k) {
  if (is_point(c)) return std::pow(c.mean, k);
  switch (c.kind) {
    case PsdComponent::Kind::gauss: {
      // X = mean + sd Y: binomial expansion over the truncated standard moments.
      const auto [lo, hi] = gauss_window(c);
      const auto m = truncated_normal_moments(lo, hi);
      constexpr std::array<std::array<double, 4>, 4> binom{
          {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}}};
      double sum = 0;
      for (int j = 0; j <= k; ++j) {
        sum += binom[k][j] * std::pow(c.mean, k - j) * std::pow(c.sd, j) * m[j];
      }
      return sum;
    }
    case PsdComponent::Kind::lognormal: {
      // E[X^k; a <= X <= b] = exp(k mu + k^2 sigma^2 / 2) (Phi(b' - k sigma) - Phi(a' - k sigma))
      // / (Phi(b') - Phi(a')), a', b' the standardised log window.
      const auto [lo, hi] = lognormal_window(c);
      const double ks = k * c.sigma;
      return std::exp(k * c.mu + 0.5 * ks * ks) * normal_mass(lo - ks, hi - ks) /
             normal_mass(lo, hi);
    }
    case PsdComponent::Kind::table: {
      // Uniform within each bin: E[X^k] = sum f_i (b^{k+1} - a^{k+1}) / ((k+1)(b - a)).
      double sum = 0;
      for (std::size_t i = 0; i + 1 < c.edges.size(); ++i) {
        const double a = c.edges[i];
        const double b = c.edges[i + 1];
        sum += c.fractions[i] * (std::pow(b, k + 1) - std::pow(a, k + 1)) / ((k + 1) * (b - a));
      }
      return sum;
    }
    case PsdComponent::Kind::mono:
      break;
  }
  return 0;
}

// Inverse CDF of the component's size variable at u in [0, 1) (docs/physics.md §1).
double quantile_variable(const PsdComponent& c, double u) {
  if (is_point(c)) return c.mean;
  switch (c.kind) {
    case PsdComponent::Kind::gauss: {
      const auto [lo, hi] = gauss_window(c);
      return std::clamp(c.mean + c.sd * truncated_normal_quantile(lo, hi, u), c.min, c.max);
    }
    case PsdComponent::Kind::lognormal: {
      const auto [lo, hi] = lognormal_window(c);
      return std::clamp(std::exp(c.mu + c.sigma * truncated_normal_quantile(lo, hi, u)), c.min,
                        c.max);
    }
    case PsdComponent::Kind::table: {
      // The CDF is piecewise linear: find the bin holding u, interpolate inside it.
      double below = 0;
      std::size_t last = 0;
      for (std::size_t i = 0; i < c.fractions.size(); ++i) {
        if (c.fractions[i] <= 0) continue;
        last = i;
        if (u < below + c.fractions[i]) {
          const double t = (u - below) / c.fractions[i];
          return c.edges[i] + t * (c.edges[i + 1] - c.edges[i]);
        }
        below += c.fractions[i];
      }
      return c.edges[last + 1];  // u beyond the rounded sum of the fractions
    }
    case PsdComponent::Kind::mono:
      break;
  }
  return c.mean;
}

double mixture_cdf(const std::vector<PsdComponent>& components, double radius, bool left) {
  double sum = 0;
  for (const auto& c : components) {
    sum += c.number_fraction * cdf_variable(c, radius / radius_scale(c), left);
  }
  return std::min(sum, 1.0);
}

}  // namespace

double radius_moment(const PsdComponent& component, int k) {
  return std::pow(radius_scale(component), k) * moment_variable(component, k);
}

double cdf_radius(const PsdComponent& component, double radius) {
  return cdf_variable(component, radius / radius_scale(component), false);
}

double quantile_radius(const PsdComponent& component, double u) {
  return radius_scale(component) * quantile_variable(component, u);
}

double window_mass(const PsdComponent& component) {
  switch (component.kind) {
    case PsdComponent::Kind::gauss: {
      if (component.sd == 0) {
        return component.min <= component.mean && component.mean <= component.max ? 1.0 : 0.0;
      }
      const auto [lo, hi] = gauss_window(component);
      return normal_mass(lo, hi);
    }
    case PsdComponent::Kind::lognormal: {
      const auto [lo, hi] = lognormal_window(component);
      return normal_mass(lo, hi);
    }
    case PsdComponent::Kind::mono:
    case PsdComponent::Kind::table:
      break;
  }
  return 1;
}

Psd Psd::mono_radius(double radius) {
  if (!(radius > 0) || !std::isfinite(radius)) {
    throw InputError(fmt::format("mono PSD: radius {:g} (accepted: finite, > 0)", radius));
  }
  Psd psd;
  PsdComponent c;
  c.kind = PsdComponent::Kind::mono;
  c.on = SizeVariable::radius;
  c.mean = c.min = c.max = radius;
  psd.components_.push_back(c);
  psd.text_ = fmt::format("mono:r={:.17g}", radius);
  return psd;
}

// docs/physics.md §1: one uniform draw picks the component by number fraction, a second one is pushed
// through that component's inverse CDF.
double Psd::sample_radius(Rng& rng) const {
  const double pick = uniform01(rng);
  const double u = uniform01(rng);
  double below = 0;
  for (const auto& c : components_) {
    below += c.number_fraction;
    if (pick < below) return quantile_radius(c, u);
  }
  return quantile_radius(components_.back(), u);
}

double Psd::cdf_radius(double radius) const { return mixture_cdf(components_, radius, false); }

double Psd::min_radius() const {
  double r = std::numeric_limits<double>::infinity();
  for (const auto& c : components_) {
    const double lowest = c.kind == PsdComponent::Kind::table ? c.edges.front()
                          : is_point(c)                       ? c.mean
                                                              : c.min;
    r = std::min(r, radius_scale(c) * lowest);
  }
  return r;
}

double Psd::max_radius() const {
  double r = 0;
  for (const auto& c : components_) {
    const double highest = c.kind == PsdComponent::Kind::table ? c.edges.back()
                           : is_point(c)                       ? c.mean
                                                               : c.max;
    r = std::max(r, radius_scale(c) * highest);
  }
  return r;
}

namespace {
double mixture_moment(const std::vector<PsdComponent>& components, int k) {
  double sum = 0;
  for (const auto& c : components) sum += c.number_fraction * radius_moment(c, k);
  return sum;
}
}  // namespace

double Psd::mean_radius() const { return mixture_moment(components_, 1); }
double Psd::mean_radius_squared() const { return mixture_moment(components_, 2); }
double Psd::mean_radius_cubed() const { return mixture_moment(components_, 3); }

std::size_t Psd::total_count() const {
  std::size_t sum = 0;
  for (const auto& c : components_) sum += c.count;
  return sum;
}

const char* basis_name(PsdBasis basis) { return basis == PsdBasis::volume ? "volume" : "number"; }

double sample_diameter_quantile(std::vector<double> radii, double q, PsdBasis basis) {
  if (radii.empty()) return 0;
  std::sort(radii.begin(), radii.end());
  const auto weight = [basis](double r) { return basis == PsdBasis::volume ? r * r * r : 1.0; };
  double total = 0;
  for (const double r : radii) total += weight(r);
  double cumulative = 0;
  for (const double r : radii) {
    cumulative += weight(r);
    if (cumulative >= q * total) return 2 * r;
  }
  return 2 * radii.back();
}

// sup |F_n - F| is reached at a sample value, on one side of the step of F_n there: compare
// F_n(v) with F(v) and F_n(v-) with F(v-) for every distinct sampled value v (ties and point
// masses of mono components included).
double ks_distance(std::vector<double> radii, const Psd& psd) {
  if (radii.empty()) return 0;
  std::sort(radii.begin(), radii.end());
  const double n = static_cast<double>(radii.size());
  double d = 0;
  std::size_t i = 0;
  while (i < radii.size()) {
    std::size_t j = i;
    while (j < radii.size() && radii[j] == radii[i]) ++j;
    const double below = mixture_cdf(psd.components(), radii[i], true);
    const double upto = mixture_cdf(psd.components(), radii[i], false);
    d = std::max({d, std::abs(static_cast<double>(i) / n - below),
                  std::abs(static_cast<double>(j) / n - upto)});
    i = j;
  }
  return d;
}

}  // namespace powderbed::bed
