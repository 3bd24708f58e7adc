#include "powderbed/thermal/enthalpy.hpp"

#include <algorithm>
#include <cmath>

namespace powderbed::thermal {

EnthalpyCurve::EnthalpyCurve(const Material& material, Per per, double reference, double t_low,
                             double t_high, std::size_t table_size)
    : material_(material), per_(per), t_low_(t_low), t_high_(t_high) {
  nodes_.push_back(t_low);
  for (const double b : material.breakpoints())
    if (b > t_low && b < t_high) nodes_.push_back(b);
  nodes_.push_back(t_high);
  cumulative_.assign(nodes_.size(), 0.0);
  for (std::size_t k = 1; k < nodes_.size(); ++k)
    cumulative_[k] = cumulative_[k - 1] + integral(nodes_[k - 1], nodes_[k]);
  // Shift so that enthalpy(reference) = 0.
  const double offset = enthalpy(reference);
  for (auto& c : cumulative_) c -= offset;

  e_low_ = cumulative_.front();
  e_high_ = cumulative_.back();
  // Beyond the ends every property is held, so the capacity just inside is the one outside.
  capacity_low_ = capacity(t_low + 1e-9 * (t_high - t_low));
  capacity_high_ = capacity(t_high - 1e-9 * (t_high - t_low));
  min_capacity_ = std::min(capacity_low_, capacity_high_);
  for (std::size_t k = 0; k + 1 < nodes_.size(); ++k) {  // linear pieces: check both ends
    const double eps = 1e-9 * (nodes_[k + 1] - nodes_[k]);
    min_capacity_ = std::min({min_capacity_, capacity(nodes_[k] + eps),
                              capacity(nodes_[k + 1] - eps)});
  }

  // The inverse table: walk the intervals once, solving enthalpy(T) = e by Newton inside the
  // interval (the integrand is smooth there), bisection as a safeguard.
  temps_.resize(table_size);
  const double step = (e_high_ - e_low_) / static_cast<double>(table_size - 2);
  // Start the table on a whole number of steps below 0, so that e = 0 is a table point and
  // maps back to the reference temperature exactly (untouched nodes stay exactly at T0).
  table_low_ = -std::ceil(-e_low_ / step) * step;
  inv_step_ = 1 / step;
  last_ = static_cast<double>(table_size - 1);
  std::size_t seg = 0;
  for (std::size_t k = 0; k < table_size; ++k) {
    const double target = table_low_ + step * static_cast<double>(k);
    if (target <= e_low_ || target >= e_high_) {  // beyond the ends: the held capacities
      temps_[k] = target <= e_low_ ? t_low_ + (target - e_low_) / capacity_low_
                                   : t_high_ + (target - e_high_) / capacity_high_;
      continue;
    }
    while (seg + 2 < nodes_.size() && cumulative_[seg + 1] < target) ++seg;
    double lo = nodes_[seg], hi = nodes_[seg + 1];
    double t = lo + (hi - lo) * std::clamp((target - cumulative_[seg]) /
                                               (cumulative_[seg + 1] - cumulative_[seg]),
                                           0.0, 1.0);
    for (int iter = 0; iter < 60; ++iter) {
      const double residual = cumulative_[seg] + integral(nodes_[seg], t) - target;
      if (residual > 0) hi = t; else lo = t;
      if (std::abs(residual) <= 1e-13 * std::abs(e_high_ - e_low_)) break;
      const double newton = t - residual / capacity(std::clamp(t, lo, hi));
      t = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    }
    temps_[k] = t;
  }
}

double EnthalpyCurve::capacity(double t) const {
  const double c = material_.apparent_heat_capacity(t);
  return per_ == Per::kilogram ? c : c * material_.density(t);
}

double EnthalpyCurve::integral(double a, double b) const {
  // Two-point Gauss–Legendre: exact for the quadratic rho(T) c(T) of one interval, and it never
  // samples the interval's ends, where c jumps at the window edges.
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  const double offset = half / std::sqrt(3.0);
  return half * (capacity(mid - offset) + capacity(mid + offset));
}

double EnthalpyCurve::enthalpy(double t) const {
  if (t <= t_low_) return e_low_ + (t - t_low_) * capacity_low_;
  if (t >= t_high_) return e_high_ + (t - t_high_) * capacity_high_;
  const auto upper = std::upper_bound(nodes_.begin(), nodes_.end(), t);
  const auto k = static_cast<std::size_t>(upper - nodes_.begin()) - 1;
  return cumulative_[k] + integral(nodes_[k], t);
}

}  // namespace powderbed::thermal
