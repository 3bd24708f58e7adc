#pragma once
// The hot wall held below where the powder melts: keff's network is a bed of solid spheres, so
// a wall at or above the material's solidus (its melting point when the file gives no solidus)
// asks for k_eff of a powder that has melted. Without a material file no bound is known but
// tungsten's melting point, 3695 K, the highest of any metal: beyond it a wall is a slip of
// units or of a digit, unless the caller trusts it. (gas.model = air bounds the walls to its fit's
// 175-1900 K in the scene's own checks.)
#include "powderbed/bed/material_file.hpp"

namespace powderbed::keff {

// Throws InputError naming the hot wall and the bound. `material`: the bed's material file, or
// null when none was named.
void check_hot_wall(double hot_temperature, const bed::MaterialFile* material, bool trust_units);

}  // namespace powderbed::keff
