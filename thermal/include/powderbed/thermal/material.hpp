#pragma once
// Temperature-dependent material of the DE–FD solver (docs/physics.md §5): a solid property table read
// from CSV, one liquid row, and the phase-change parameters of the apparent heat capacity.
#include <string>
#include <vector>

#include "powderbed/bed/option_words.hpp"

namespace powderbed::thermal {

// The property table of a material file (bed/material_file.hpp: columns temperature_K,
// specific_heat_J_per_kgK, conductivity_W_per_mK, density_kg_per_m3, phase = solid | liquid).
struct MaterialTable {
  std::vector<double> temperature, specific_heat, conductivity, density;  // solid rows
  double liquid_specific_heat = 0, liquid_conductivity = 0, liquid_density = 0;
};

// Reads the table of a material file with bed::read_material_file: at least two solid rows with
// strictly increasing temperature, one liquid row, every value finite and positive. Throws
// InputError naming the file, the line and what is accepted, or that the file has no table.
MaterialTable read_material_table(const std::string& path);

// Phase-change and scene-level material parameters ([GZ] Table 2 defaults).
struct PhaseChange {
  double melting_point = 1700;     // T_m, K
  double boiling_point = 3130;     // T_v, K
  double latent_melt = 2.99e5;     // L_m, J/kg
  double latent_vapour = 6.09e6;   // L_v, J/kg
  double window = 20;              // ΔT of the apparent heat capacity, K
};

enum class LiquidConductivity { solid, table };  // [GZ] keep the solid value in the liquid
inline constexpr bed::OptionWord<LiquidConductivity> kLiquidConductivityWords[] = {
    {"solid", LiquidConductivity::solid}, {"table", LiquidConductivity::table}};

// Properties as functions of temperature. Solid: the table interpolated linearly, held at the
// first row below it, extrapolated linearly from the last two rows up to `hold_from`, constant
// from there to the melting window. Liquid and gas (no gas data in [GZ]: the liquid values) from
// the liquid row. Across a phase-change window the conductivity and density blend linearly.
class Material {
 public:
  Material(MaterialTable table, PhaseChange phase, double hold_from,
           LiquidConductivity liquid_conductivity);

  double solid_specific_heat(double t) const { return solid(table_.specific_heat, t); }
  double solid_conductivity(double t) const { return solid(table_.conductivity, t); }
  double solid_density(double t) const { return solid(table_.density, t); }
  double liquid_specific_heat() const { return table_.liquid_specific_heat; }
  double liquid_conductivity() const { return liquid_conductivity_; }
  double liquid_density() const { return table_.liquid_density; }

  // Apparent heat capacity c(T), J/kgK (docs/physics.md §5, the five-branch formula).
  double apparent_heat_capacity(double t) const;
  double conductivity(double t) const;
  double density(double t) const;
  // 0 solid, 1 liquid, 2 gas: the phase whose window T has passed the middle of.
  unsigned phase(double t) const;

  const PhaseChange& phase_change() const { return phase_; }
  // Temperatures where c, k or rho change their formula (table rows, hold_from, window edges),
  // sorted: between two of them every property is a linear function of T.
  const std::vector<double>& breakpoints() const { return breakpoints_; }

 private:
  double solid(const std::vector<double>& column, double t) const;

  MaterialTable table_;
  PhaseChange phase_;
  double hold_from_;
  double liquid_conductivity_;
  std::vector<double> breakpoints_;
};

// Throws InputError unless T_m < T_v, the windows do not overlap and the hold temperature lies
// between the last table row and the melting window, all values finite and positive.
void validate(const PhaseChange& phase, double hold_from, const MaterialTable& table);

}  // namespace powderbed::thermal
