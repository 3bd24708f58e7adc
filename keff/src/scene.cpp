#include "powderbed/keff/scene.hpp"

#include <cmath>
#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"

namespace powderbed::keff {
namespace {

bool positive(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

ContactRadiusParams contact_radius_params(const bed::ContactProvenance& made,
                                          bool hertz_correction, const ContactOptions& given) {
  const auto require = require_in_range;  // bed/errors.hpp
  if (given.law && *given.law != "hertz" && *given.law != "linear")
    throw InputError("contact.law: '" + *given.law + "' (accepted: hertz, linear)");
  if (given.young_scale)
    require(positive(*given.young_scale), "contact.young-scale", *given.young_scale, "S > 0");
  if (given.stiffness)
    require(positive(*given.stiffness), "contact.stiffness", *given.stiffness, "k_n > 0 N/m");
  if (given.young) require(positive(*given.young), "contact.young", *given.young, "E > 0 Pa");
  ContactRadiusParams p;
  p.hertz_correction = hertz_correction;
  if (made.law.empty()) {
    if (hertz_correction)
      throw InputError("contact.hertz-correction: the bed records no contact law, E, nu or "
                       "softening (accepted: a bed written by deposit, or "
                       "contact.hertz-correction = false for the geometric contact circle)");
    return p;
  }
  // One line naming the option, its value and the bed's.
  const auto contradicts = [](const char* option, const std::string& value,
                              const std::string& bed_value) {
    throw InputError(std::string(option) + ": " + value + " contradicts the bed, made with " +
                     bed_value + " (accepted: " + bed_value + ", or leave it out: it is read "
                     "from the bed)");
  };
  const auto number = [](double v) { return fmt::format("{:g}", v); };
  const auto differs = [](double a, double b) { return std::abs(a - b) > 1e-12 * std::abs(b); };
  if (given.law && *given.law != made.law) contradicts("contact.law", *given.law, made.law);
  if (hertz_correction && made.fines_stiffness_radius > 0)
    throw InputError(fmt::format(
        "contact.hertz-correction: the bed's particles below r = {:g} m ran with E (r/R)^2 "
        "(deposit fines.scaling = stiffness), which the correction does not model (accepted: "
        "contact.hertz-correction = false, or a bed deposited without stiffness scaling)",
        made.fines_stiffness_radius));
  p.law = made.law == "linear" ? BedContactLaw::linear : BedContactLaw::hertz;
  if (p.law == BedContactLaw::linear) {
    if (given.young_scale && *given.young_scale != 1)
      contradicts("contact.young-scale", number(*given.young_scale), "the linear law (S = 1)");
    if (given.stiffness && differs(*given.stiffness, made.stiffness))
      contradicts("contact.stiffness", number(*given.stiffness),
                  "k_n = " + number(made.stiffness) + " N/m");
  } else {
    if (given.stiffness)
      contradicts("contact.stiffness", number(*given.stiffness), "the hertz law (no k_n)");
    if (given.young_scale && differs(*given.young_scale, made.young_scale))
      contradicts("contact.young-scale", number(*given.young_scale),
                  "young-scale " + number(made.young_scale));
  }
  if (!hertz_correction) return p;
  require(positive(made.young), "the bed's contact_young", made.young, "E > 0 Pa");
  require(positive(made.wall_young), "the bed's contact_wall_young", made.wall_young, "E > 0 Pa");
  // E' read for the particles; the walls' modulus scaled alike (the same material in [KE]).
  const double factor = given.young ? *given.young / made.young : 1.0;
  if (p.law == BedContactLaw::linear) {
    require(positive(made.stiffness), "the bed's contact_stiffness", made.stiffness,
            "k_n > 0 N/m");
    const double e = made.young * factor, e_wall = made.wall_young * factor;
    const auto star = [](double e_i, double nu_i, double e_j, double nu_j) {
      return 1.0 / ((1 - nu_i * nu_i) / e_i + (1 - nu_j * nu_j) / e_j);
    };
    p.stiffness = made.stiffness;
    p.pair_modulus = star(e, made.poisson, e, made.poisson);
    p.wall_modulus = star(e, made.poisson, e_wall, made.wall_poisson);
  } else {
    require(positive(made.young_scale), "the bed's contact_young_scale", made.young_scale, "S > 0");
    p.young_scale = made.young_scale * factor;
  }
  return p;
}

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
  require(rays >= 1 && rays <= 1000000000, "rays", static_cast<double>(rays),
          "1 to 1e9 rays per particle");
  require(newton_tolerance > 0 && newton_tolerance < 1e-2, "newton-tolerance", newton_tolerance,
          "0 < tolerance < 1e-2");
  if (!contact_path && !gas_path && !radiation_path)
    throw InputError(
        "effects: contact, gas and radiation are all off (accepted: at least one heat path)");
}

}  // namespace powderbed::keff
