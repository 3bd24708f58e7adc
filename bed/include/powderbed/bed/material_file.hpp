#pragma once
// A powder's material file (data/materials/<NAME>.csv): the one place a material's numbers live,
// read once here for every program (deposit's elastic constants, sinter's property table and
// phase change, keff's solid conductivity). docs/physics.md "Materials" describes the format:
//   # comments
//   property,value,unit,source            (header of the scalar block, optional)
//   name,<NAME>                           (one line each; the text is the rest of the line)
//   description,<one line>
//   <key>,<number>,<unit>,<source: the rest of the line, commas allowed>
//   temperature_K,specific_heat_J_per_kgK,conductivity_W_per_mK,density_kg_per_m3,phase[,source]
//   <T>,<c>,<k>,<rho>,solid|liquid[,source]   (solid rows, T increasing, then one liquid row)
// Every number is finite and positive; each key's unit must be the one of kMaterialKeys, so a
// file in other units is refused instead of read wrongly.
#include <optional>
#include <string>
#include <vector>

namespace powderbed::bed {

// The scalar properties a material file may give: key, its SI unit, the accepted range.
struct MaterialKey {
  const char* key;
  const char* unit;
  double min, max;  // accepted: min < value <= max
  const char* meaning;
};
inline constexpr MaterialKey kMaterialKeys[] = {
    {"density", "kg/m^3", 0, 1e5, "solid density at room temperature (DEM particle mass)"},
    {"young_modulus", "Pa", 0, 1e13, "Young's modulus E at room temperature"},
    {"poisson_ratio", "1", 0, 0.5, "Poisson's ratio nu"},
    {"solidus", "K", 0, 1e4, "solidus temperature"},
    {"liquidus", "K", 0, 1e4, "liquidus temperature"},
    {"melting_point", "K", 0, 1e4,
     "T_m of the apparent heat capacity (solidus <= T_m <= liquidus)"},
    {"boiling_point", "K", 0, 1e5, "T_v"},
    {"latent_melt", "J/kg", 0, 1e8, "latent heat of melting L_m"},
    {"latent_vapour", "J/kg", 0, 1e9, "latent heat of vaporisation L_v"},
    {"hold_from", "K", 0, 1e4, "solid rows extrapolated to this temperature, then held"},
    {"absorptivity", "1", 0, 1, "absorptivity of the flat surface at the laser's wavelength"},
    {"index_n_solid", "1", 0, 100, "refractive index n of the solid at the laser's wavelength"},
    {"index_k_solid", "1", 0, 100, "extinction coefficient k of the solid at the laser's wavelength"},
    {"index_n_liquid", "1", 0, 100, "refractive index n of the liquid at the laser's wavelength"},
    {"index_k_liquid", "1", 0, 100, "extinction coefficient k of the liquid"},
    {"molar_mass", "kg/mol", 0, 1, "molar mass of the vapour (evaporation)"},
    {"surface_tension", "N/m", 0, 10, "surface tension of the liquid near T_m"},
};

struct MaterialProperty {
  std::string key;
  double value = 0;
  std::string source;
};

// One table row: a solid row or the liquid row.
struct MaterialRow {
  double temperature = 0, specific_heat = 0, conductivity = 0, density = 0;
  bool liquid = false;
  std::string source;
};

struct MaterialFile {
  std::string path, name, description;
  std::vector<MaterialProperty> properties;  // in file order
  std::vector<MaterialRow> solid;            // increasing temperature; empty: no table
  std::optional<MaterialRow> liquid;

  // The value of `key` (one of kMaterialKeys), if the file gives it.
  std::optional<double> get(const std::string& key) const;
  // Solid conductivity at `temperature` from the table: linear between rows, held beyond them.
  // Throws InputError naming the file when it has no table.
  double solid_conductivity(double temperature) const;
};

// Reads and checks a material file. Throws InputError naming the file, the line and what is
// accepted: an unknown key or unit, a value out of range, a non-number, a table with fewer than
// two solid rows or no liquid row, temperatures that do not increase, solidus > T_m > liquidus.
MaterialFile read_material_file(const std::string& path);

// The folder of the shipped material files (the source tree's data/materials, fixed at build).
std::string materials_folder();
// A material name (316L, Ti-6Al-4V, ...: a file <name>.csv in materials_folder()) or a path
// (anything with a '/' or ending in .csv) to the file it names. Throws InputError naming
// `option` and listing the shipped names for an unknown name.
std::string material_path(const std::string& name_or_path, const std::string& option);
// The shipped materials, sorted by name.
std::vector<MaterialFile> shipped_materials();

}  // namespace powderbed::bed
