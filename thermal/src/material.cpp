#include "powderbed/thermal/material.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "powderbed/bed/errors.hpp"
#include "powderbed/thermal/apparent_heat_capacity.hpp"

namespace powderbed::thermal {

namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) {
    const auto first = field.find_first_not_of(" \t\r");
    const auto last = field.find_last_not_of(" \t\r");
    fields.push_back(first == std::string::npos ? "" : field.substr(first, last - first + 1));
  }
  return fields;
}

double parse_value(const std::string& text, const std::string& where, const char* column) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !std::isfinite(value) || value <= 0) {
    throw InputError(where + ": " + column + " '" + text +
                     "' is not a finite positive number (accepted: value > 0)");
  }
  return value;
}

double blend(double a, double b, double t, double t0, double t1) {
  return a + (b - a) * (t - t0) / (t1 - t0);
}

}  // namespace

MaterialTable read_material_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the material table");
  MaterialTable table;
  bool header = false, liquid = false;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(number);
    const auto fields = split_fields(line);
    if (!header) {  // the column names; the order is fixed
      if (fields.size() != 5 || fields[0].rfind("temperature", 0) != 0) {
        throw InputError(where + ": header '" + line + "' (accepted: temperature_K,"
                         "specific_heat_J_per_kgK,conductivity_W_per_mK,density_kg_per_m3,phase)");
      }
      header = true;
      continue;
    }
    if (fields.size() != 5) {
      throw InputError(where + ": " + std::to_string(fields.size()) +
                       " fields (accepted: 5: T, c, k, rho, phase)");
    }
    const double t = parse_value(fields[0], where, "temperature");
    const double c = parse_value(fields[1], where, "specific heat");
    const double k = parse_value(fields[2], where, "conductivity");
    const double rho = parse_value(fields[3], where, "density");
    if (fields[4] == "solid") {
      if (liquid) throw InputError(where + ": solid row after the liquid row (accepted: solid "
                                   "rows first, then one liquid row)");
      if (!table.temperature.empty() && t <= table.temperature.back()) {
        throw InputError(where + ": temperature " + fields[0] +
                         " K does not increase (accepted: strictly increasing solid rows)");
      }
      table.temperature.push_back(t);
      table.specific_heat.push_back(c);
      table.conductivity.push_back(k);
      table.density.push_back(rho);
    } else if (fields[4] == "liquid") {
      if (liquid) throw InputError(where + ": a second liquid row (accepted: one)");
      liquid = true;
      table.liquid_specific_heat = c;
      table.liquid_conductivity = k;
      table.liquid_density = rho;
    } else {
      throw InputError(where + ": phase '" + fields[4] + "' (accepted: solid or liquid)");
    }
  }
  if (table.temperature.size() < 2 || !liquid) {
    throw InputError(path + ": " + std::to_string(table.temperature.size()) + " solid rows and " +
                     (liquid ? "one" : "no") +
                     " liquid row (accepted: at least 2 solid rows and one liquid row)");
  }
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
