#include "powderbed/thermal/material.hpp"

#include <algorithm>
#include <cmath>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/material_file.hpp"
#include "powderbed/thermal/apparent_heat_capacity.hpp"

namespace powderbed::thermal {

namespace {

double blend(double a, double b, double t, double t0, double t1) {
  return a + (b - a) * (t - t0) / (t1 - t0);
}

}  // namespace

MaterialTable read_material_table(const std::string& path) {
  const bed::MaterialFile file = bed::read_material_file(path);
  if (file.solid.empty())
    throw InputError(path + ": no property table (accepted: solid rows and one liquid row after "
                     "the header temperature_K,...,phase)");
  MaterialTable table;
  for (const auto& row : file.solid) {
    table.temperature.push_back(row.temperature);
    table.specific_heat.push_back(row.specific_heat);
    table.conductivity.push_back(row.conductivity);
    table.density.push_back(row.density);
  }
  table.liquid_specific_heat = file.liquid->specific_heat;
  table.liquid_conductivity = file.liquid->conductivity;
  table.liquid_density = file.liquid->density;
  return table;
}

void validate(const PhaseChange& phase, double hold_from, const MaterialTable& table) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0; };
  const double half = 0.5 * phase.window;
  require_in_range(positive(phase.window), "material.window", phase.window, "ΔT > 0 K");
  require_in_range(non_negative(phase.latent_melt), "material.latent-melt", phase.latent_melt,
                   "L_m >= 0 J/kg");
  require_in_range(non_negative(phase.latent_vapour), "material.latent-vapour",
                   phase.latent_vapour, "L_v >= 0 J/kg");
  require_in_range(positive(phase.melting_point) &&
                       phase.melting_point - half > table.temperature.back(),
                   "material.melting-point", phase.melting_point,
                   "T_m - ΔT/2 above the last solid row of the table");
  require_in_range(phase.boiling_point - half > phase.melting_point + half,
                   "material.boiling-point", phase.boiling_point, "T_v - ΔT/2 > T_m + ΔT/2");
  require_in_range(hold_from >= table.temperature.back() && hold_from <= phase.melting_point - half,
                   "material.hold-from", hold_from, "between the last solid row and T_m - ΔT/2");
}

Material::Material(MaterialTable table, PhaseChange phase, double hold_from,
                   LiquidConductivity liquid_conductivity)
    : table_(std::move(table)), phase_(phase), hold_from_(hold_from) {
  validate(phase_, hold_from_, table_);
  liquid_conductivity_ = liquid_conductivity == LiquidConductivity::table
                             ? table_.liquid_conductivity
                             : solid(table_.conductivity, hold_from_);
  breakpoints_ = table_.temperature;
  const double half = 0.5 * phase_.window;
  for (const double t : {hold_from_, phase_.melting_point - half, phase_.melting_point + half,
                         phase_.boiling_point - half, phase_.boiling_point + half}) {
    breakpoints_.push_back(t);
  }
  std::sort(breakpoints_.begin(), breakpoints_.end());
  breakpoints_.erase(std::unique(breakpoints_.begin(), breakpoints_.end()), breakpoints_.end());
}

double Material::solid(const std::vector<double>& column, double t) const {
  const auto& temps = table_.temperature;
  if (t <= temps.front()) return column.front();
  const double t_eval = std::min(t, hold_from_);
  auto upper = std::upper_bound(temps.begin(), temps.end(), t_eval);
  if (upper == temps.end()) --upper;  // beyond the table: extrapolate from the last two rows
  const std::size_t k = static_cast<std::size_t>(upper - temps.begin());
  return blend(column[k - 1], column[k], t_eval, temps[k - 1], temps[k]);
}

double Material::apparent_heat_capacity(double t) const {
  const ApparentHeatCapacityParams p{phase_.melting_point, phase_.boiling_point, phase_.window,
                                     phase_.latent_melt, phase_.latent_vapour};
  const double c_liquid = table_.liquid_specific_heat;
  return thermal::apparent_heat_capacity(t, solid_specific_heat(t), c_liquid, c_liquid, p);
}

// Conductivity and density: solid below the melting window, liquid above it, linear in between
// (the gas keeps the liquid values; vaporised particles leave the network, solver.hpp).
double Material::conductivity(double t) const {
  const double lo = phase_.melting_point - 0.5 * phase_.window;
  const double hi = phase_.melting_point + 0.5 * phase_.window;
  if (t <= lo) return solid_conductivity(t);
  if (t >= hi) return liquid_conductivity_;
  return blend(solid_conductivity(lo), liquid_conductivity_, t, lo, hi);
}

double Material::density(double t) const {
  const double lo = phase_.melting_point - 0.5 * phase_.window;
  const double hi = phase_.melting_point + 0.5 * phase_.window;
  if (t <= lo) return solid_density(t);
  if (t >= hi) return table_.liquid_density;
  return blend(solid_density(lo), table_.liquid_density, t, lo, hi);
}

unsigned Material::phase(double t) const {
  if (t < phase_.melting_point) return 0;
  return t < phase_.boiling_point ? 1u : 2u;
}

}  // namespace powderbed::thermal
