#pragma once
// What a material file (material_file.hpp) fills, program by program: the option, the field of
// the program's scene struct that option is bound to (the Python module's keyword, dotted for a
// nested struct), and the file's key. One table for the programs' --material and the Python
// module's material="NAME", so the two fill the same numbers.
//
// Two keys are not scalars: "file" is the material file itself (sinter reads its table),
// "conductivity" the table's solid conductivity at the bed's temperature (keff: the mean of the
// walls). A required key is one the program's models always read: a file without it is refused
// unless the option is given beside it, since the option's default is 316L's (wrong for any
// other metal). The keys only some models read (optics, evaporation) are checked by the program
// that knows its models (sinter: require_material_keys).
#include <optional>
#include <string>
#include <variant>

#include "powderbed/bed/material_file.hpp"

namespace powderbed::bed {

struct MaterialFill {
  const char* program;
  const char* option;
  const char* field;
  const char* key;
  bool required;
};
inline constexpr MaterialFill kMaterialFills[] = {
    {"deposit", "material.density", "material.density", "density", true},
    {"deposit", "material.young", "material.young", "young_modulus", true},
    {"deposit", "material.poisson", "material.poisson", "poisson_ratio", true},
    {"sinter", "material.table", "material_table", "file", true},
    {"sinter", "material.melting-point", "phase_change.melting_point", "melting_point", true},
    {"sinter", "material.boiling-point", "phase_change.boiling_point", "boiling_point", false},
    {"sinter", "material.latent-melt", "phase_change.latent_melt", "latent_melt", true},
    {"sinter", "material.latent-vapour", "phase_change.latent_vapour", "latent_vapour", false},
    {"sinter", "material.hold-from", "hold_from", "hold_from", true},
    {"sinter", "laser.absorptivity", "absorptivity", "absorptivity", false},
    {"sinter", "laser.index-n-solid", "index_n_solid", "index_n_solid", false},
    {"sinter", "laser.index-k-solid", "index_k_solid", "index_k_solid", false},
    {"sinter", "laser.index-n-liquid", "index_n_liquid", "index_n_liquid", false},
    {"sinter", "laser.index-k-liquid", "index_k_liquid", "index_k_liquid", false},
    {"sinter", "material.molar-mass", "molar_mass", "molar_mass", false},
    {"sinter", "material.surface-tension", "surface_tension", "surface_tension", false},
    {"keff", "solid.conductivity", "solid_conductivity", "conductivity", true},
};

// A fill's value: a number, or the file's path ("file").
using MaterialValue = std::variant<double, std::string>;

// The material file `name_or_path` names (material_path), read and checked; its errors name
// `option` ("--material: 'x' is not a material (accepted: 316L, ...)").
MaterialFile read_named_material(const std::string& name_or_path, const std::string& option);

// What `file` gives `fill`, the conductivity at `temperature` (K); none when it gives nothing.
std::optional<MaterialValue> material_value(const MaterialFile& file, const MaterialFill& fill,
                                            double temperature);

// The refusal of a required fill that `file` does not give: InputError naming the option.
[[noreturn]] void refuse_missing_fill(const MaterialFile& file, const MaterialFill& fill);

}  // namespace powderbed::bed
