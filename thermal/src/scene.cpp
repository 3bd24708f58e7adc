#include "powderbed/thermal/scene.hpp"

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"

namespace powderbed::thermal {

namespace {

bool positive(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

// The optics, evaporation and depression (docs/sinter.md "The melt pool at process settings").
void SinterScene::validate_process_models() const {
  const auto require = require_in_range;
  if (absorption == LaserAbsorption::ray_trace && optics == Optics::fresnel) {
    require(positive(index_n_solid), "laser.index-n-solid", index_n_solid,
            "n > 0 (the material file's index_n_solid, or laser.optics = constant)");
    require(positive(index_k_solid), "laser.index-k-solid", index_k_solid,
            "k > 0 (the material file's index_k_solid, or laser.optics = constant)");
    require(positive(index_n_liquid), "laser.index-n-liquid", index_n_liquid,
            "n > 0 (the material file's index_n_liquid, or laser.optics = constant)");
    require(positive(index_k_liquid), "laser.index-k-liquid", index_k_liquid,
            "k > 0 (the material file's index_k_liquid, or laser.optics = constant)");
  }
  if (!has(kEvaporation) && !has(kDepression)) return;
  const char* effect = has(kEvaporation) ? "effects.evaporation" : "effects.depression";
  if (integrator != Integrator::explicit_euler)
    throw InputError(fmt::format("{}: works with --integrator explicit only (accepted: "
                                 "--integrator explicit, or {} = false)",
                                 effect, effect));
  require(positive(molar_mass), "material.molar-mass", molar_mass, "M > 0 kg/mol");
  require(positive(ambient_pressure), "environment.pressure", ambient_pressure, "p0 > 0 Pa");
  require(back_condensation >= 0 && back_condensation < 1, "evaporation.back-condensation",
          back_condensation, "0 <= beta_r < 1");
  if (has(kDepression))
    require(positive(surface_tension), "material.surface-tension", surface_tension,
            "gamma > 0 N/m");
}

void SinterScene::validate() const {
  const auto require = require_in_range;  // bed/errors.hpp
  require(convection >= 0 && std::isfinite(convection), "environment.convection", convection,
          "h >= 0 W/m^2K");
  require(emissivity >= 0 && emissivity <= 1, "environment.emissivity", emissivity,
          "0 <= eps <= 1");
  require(positive(environment_temperature), "environment.temperature", environment_temperature,
          "T_env > 0 K");
  require(positive(initial_temperature), "environment.initial-temperature", initial_temperature,
          "T0 > 0 K");
  require(power >= 0 && std::isfinite(power), "power", power, "P >= 0 W");
  require(positive(speed), "speed", speed, "v > 0 m/s");
  require(positive(spot_radius), "spot", spot_radius, "w > 0 m");
  // Every option is checked whichever model reads it: a value that cannot be right is refused
  // even where the scene ignores it. alpha = 0 would reflect a ray forever between two spheres.
  require(absorptivity > 0 && absorptivity <= 1, "laser.absorptivity", absorptivity,
          "0 < alpha <= 1");
  require(std::isnan(absorptivity_liquid) || (absorptivity_liquid > 0 && absorptivity_liquid <= 1),
          "laser.absorptivity-liquid", absorptivity_liquid, "0 < alpha <= 1");
  thermal::validate(rays);
  require(retrace_interval > 0 && retrace_interval <= 1, "laser.retrace-interval",
          retrace_interval, "0 < interval <= 1 spot radius");
  require(contact_angle > 0 && contact_angle < 180, "wetting.contact-angle", contact_angle,
          "0 < theta < 180 degrees");
  require(positive(arrested_conductance), "wetting.arrested-conductance", arrested_conductance,
          "h_c > 0 W/m^2K");
  if (absorption == LaserAbsorption::ray_trace && integrator != Integrator::explicit_euler)
    throw InputError("laser.absorption: ray-trace works with --integrator explicit only "
                     "(accepted: --integrator explicit, or laser.absorption = beer-lambert)");
  if (has(kWetting) && integrator != Integrator::explicit_euler)
    throw InputError("effects.wetting: works with --integrator explicit only (accepted: "
                     "--integrator explicit, or effects.wetting = false)");
  require(positive(substrate_depth), "substrate.depth", substrate_depth, "depth > 0 m");
  if (periodic_y && integrator != Integrator::explicit_euler)
    throw InputError("substrate.periodic: y works with --integrator explicit only (accepted: "
                     "--integrator explicit, or substrate.periodic = none)");
  static const char* axis[] = {"x", "y", "z"};
  for (std::size_t a = 0; a < 3; ++a) {
    if (nodes[a] < 3) {
      throw InputError(fmt::format("substrate.nodes: {} nodes along {} (accepted: at least 3 per "
                                   "direction, so that one node is free)",
                                   nodes[a], axis[a]));
    }
  }
  require(dt >= 0 && std::isfinite(dt), "dt", dt, "dt > 0 s, or 0 for the stable bound");
  require(safety > 0 && safety <= 1, "time.safety", safety, "0 < safety <= 1");
  require(positive(max_particle_rise), "time.max-particle-rise", max_particle_rise,
          "a rise > 0 K per particle step");
  require(std::isnan(t_end) || positive(t_end), "t-end", t_end, "t_end > 0 s");
  validate_process_models();
}

}  // namespace powderbed::thermal
