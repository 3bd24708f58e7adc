#include "powderbed/thermal/keff_scene.hpp"

#include <cmath>

#include "powderbed/bed/errors.hpp"

namespace powderbed::thermal {
namespace {

bool positive(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

double KeffScene::gas_conductivity_used() const {
  return gas_model == GasModel::constant
             ? gas_conductivity
             : air_conductivity((hot_temperature + cold_temperature) / 2);
}

void KeffScene::validate() const {
  const auto require = require_in_range;  // bed/errors.hpp
  require(axis >= 0 && axis <= 2, "axis", axis, "x, y or z");
  require(positive(cold_temperature), "t-cold", cold_temperature, "T_cold > 0 K");
  require(std::isfinite(hot_temperature) && hot_temperature > cold_temperature, "t-hot",
          hot_temperature, "T_hot > T_cold");
  if (gas_model == GasModel::air) {
    // Every gas link lies between the wall temperatures at the steady state.
    require(cold_temperature >= 175, "gas.model = air: t-cold", cold_temperature,
            "175-1900 K, the range of the [KE] fit");
    require(hot_temperature <= 1900, "gas.model = air: t-hot", hot_temperature,
            "175-1900 K, the range of the [KE] fit");
  }
  require(positive(solid_conductivity), "solid.conductivity", solid_conductivity, "k_s > 0 W/mK");
  require(gas_conductivity >= 0 && std::isfinite(gas_conductivity), "gas.conductivity",
          gas_conductivity, "k_g >= 0 W/mK");
  require(positive(calibration), "contact.calibration", calibration, "A_c > 0");
  require(positive(contact.young_scale), "contact.young-scale", contact.young_scale, "S > 0");
  require(positive(lens.lens), "gas.lens", lens.lens, "lens thickness / radius > 0");
  require(positive(lens.min_gap), "gas.min-gap", lens.min_gap, "l_min > 0 m");
  require(emissivity > 0 && emissivity <= 1, "radiation.emissivity", emissivity, "0 < e <= 1");
  require(wall_emissivity > 0 && wall_emissivity <= 1, "radiation.wall-emissivity",
          wall_emissivity, "0 < e <= 1");
  // The upper bound keeps the per-particle hit counts (32-bit) exact and catches a negative
  // number wrapped by the option parser.
  require(rays >= 1 && rays <= 1000000000, "radiation.rays", static_cast<double>(rays),
          "1 to 1e9 rays per particle");
  require(newton_tolerance > 0 && newton_tolerance < 1e-2, "newton-tolerance", newton_tolerance,
          "0 < tolerance < 1e-2");
  if (!contact_path && !gas_path && !radiation_path)
    throw InputError(
        "effects: contact, gas and radiation are all off (accepted: at least one heat path)");
}

}  // namespace powderbed::thermal
