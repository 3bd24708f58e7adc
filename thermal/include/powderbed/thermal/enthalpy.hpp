#pragma once
// Enthalpy form of the apparent heat capacity (docs/physics.md §5). The solver keeps each particle's
// specific enthalpy h (J/kg) and each substrate node's volumetric enthalpy e (J/m^3) as its
// state: a forward-Euler step adds energy exactly (energy is conserved to round-off whatever
// the window ΔT), and T follows from the inverse h -> T. With e(T) = ∫ rho(T) c(T) dT the
// density update of the substrate's phase change is part of the state (rho c dT/dt = ∇·K∇T).
#include <vector>

#include "powderbed/thermal/material.hpp"

namespace powderbed::thermal {

class EnthalpyCurve {
 public:
  enum class Per { kilogram, cubic_metre };
  // Integrates c(T) (times rho(T) per cubic metre) from `reference` K; the inverse is tabulated
  // on `table_size` points evenly spaced in enthalpy between t_low and t_high, linear outside.
  EnthalpyCurve(const Material& material, Per per, double reference, double t_low,
                double t_high, std::size_t table_size = 1u << 16);

  // Exact integral (two-point Gauss–Legendre on each interval between breakpoints, where the
  // integrand is a polynomial of degree <= 2).
  double enthalpy(double t) const;
  // Inverse by the table: linear interpolation between exact points (e = 0 is one of them).
  double temperature(double e) const {
    const double x = (e - table_low_) * inv_step_;
    if (x <= 0) return temps_.front() + (e - table_low_) / capacity_low_;
    if (x >= last_) return temps_.back() + (e - table_low_ - last_ / inv_step_) / capacity_high_;
    const auto k = static_cast<std::size_t>(x);
    const double f = x - static_cast<double>(k);
    return temps_[k] + f * (temps_[k + 1] - temps_[k]);
  }
  // dh/dT: c(T) (per kg) or rho(T) c(T) (per m^3).
  double capacity(double t) const;
  // The smallest capacity over [t_low, t_high] (for stable steps that hold in every state).
  double min_capacity() const { return min_capacity_; }

 private:
  double integral(double a, double b) const;  // a, b within one interval

  const Material& material_;
  Per per_;
  std::vector<double> nodes_;       // breakpoints within [t_low, t_high] and both ends
  std::vector<double> cumulative_;  // enthalpy at nodes_
  double t_low_, t_high_, e_low_, e_high_, capacity_low_, capacity_high_;
  double table_low_ = 0;  // enthalpy of temps_[0]
  double inv_step_, last_, min_capacity_;
  std::vector<double> temps_;  // T at e_low + k * step
};

// f(T) sampled evenly on [t_low, t_high], linear in between, held outside: a fast conductivity
// lookup for the inner loops.
class UniformTable {
 public:
  template <class F>
  UniformTable(F f, double t_low, double t_high, double spacing)
      : t_low_(t_low), inv_step_(1 / spacing) {
    const auto n = static_cast<std::size_t>((t_high - t_low) / spacing) + 2;
    values_.resize(n);
    for (std::size_t k = 0; k < n; ++k) values_[k] = f(t_low + spacing * static_cast<double>(k));
    last_ = static_cast<double>(n - 1);
  }
  double operator()(double t) const {
    const double x = (t - t_low_) * inv_step_;
    if (x <= 0) return values_.front();
    if (x >= last_) return values_.back();
    const auto k = static_cast<std::size_t>(x);
    return values_[k] + (x - static_cast<double>(k)) * (values_[k + 1] - values_[k]);
  }

 private:
  double t_low_, inv_step_, last_ = 0;
  std::vector<double> values_;
};

}  // namespace powderbed::thermal
