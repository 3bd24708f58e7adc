#include "powderbed/dem/scene.hpp"

#include <cmath>

#include "powderbed/bed/errors.hpp"

namespace powderbed::dem {

ContactLaw parse_contact_law(const std::string& text, const std::string& option) {
  if (text == "hertz") return ContactLaw::hertz;
  if (text == "linear") return ContactLaw::linear;
  throw InputError(option + ": '" + text + "' is not a contact law (accepted: hertz, linear)");
}

FrictionModel parse_friction_model(const std::string& text, const std::string& option) {
  if (text == "sliding") return FrictionModel::sliding;
  if (text == "history") return FrictionModel::history;
  throw InputError(option + ": '" + text + "' is not a friction model (accepted: sliding, history)");
}

const char* friction_model_name(FrictionModel model) {
  return model == FrictionModel::history ? "history" : "sliding";
}

FinesScaling parse_fines_scaling(const std::string& text, const std::string& option) {
  if (text == "none") return FinesScaling::none;
  if (text == "mass") return FinesScaling::mass;
  if (text == "stiffness") return FinesScaling::stiffness;
  throw InputError(option + ": '" + text + "' is not a fines scaling (accepted: none, mass, stiffness)");
}

const char* fines_scaling_name(FinesScaling scaling) {
  switch (scaling) {
    case FinesScaling::mass: return "mass";
    case FinesScaling::stiffness: return "stiffness";
    case FinesScaling::none: break;
  }
  return "none";
}

const char* contact_law_name(ContactLaw law) {
  return law == ContactLaw::linear ? "linear" : "hertz";
}

void Scene::validate() const {
  const auto require = require_in_range;  // bed/errors.hpp
  const auto finite_positive = [](double v) { return std::isfinite(v) && v > 0; };
  require(finite_positive(material.young), "material.young", material.young, "E > 0 Pa");
  require(material.poisson >= 0 && material.poisson < 0.5, "material.poisson", material.poisson,
          "0 <= nu < 0.5");
  require(finite_positive(material.density), "material.density", material.density,
          "rho > 0 kg/m^3");
  // The stable step (time_step.hpp) is derived for at most critical damping.
  require(material.damping >= 0 && material.damping <= 1, "material.damping", material.damping,
          "0 <= zeta <= 1");
  require(material.friction >= 0 && std::isfinite(material.friction), "material.friction",
          material.friction, "mu_d >= 0");
  require(material.rolling >= 0 && std::isfinite(material.rolling), "material.rolling",
          material.rolling, "mu_r >= 0");
  require(finite_positive(wall.young), "wall.young", wall.young, "E > 0 Pa");
  require(wall.poisson >= 0 && wall.poisson < 0.5, "wall.poisson", wall.poisson, "0 <= nu < 0.5");
  if (law == ContactLaw::linear) {
    require(finite_positive(stiffness), "contact.stiffness", stiffness,
            "k_n > 0 N/m with contact.law = linear");
  }
  if (fines.scaling != FinesScaling::none) {
    require(finite_positive(fines.radius), "fines.radius", fines.radius,
            "R_ref > 0 m with fines.scaling = mass or stiffness");
    // The linear law's one k_n has no modulus to scale (its fines: fines.scaling = mass).
    if (fines.scaling == FinesScaling::stiffness && law == ContactLaw::linear) {
      throw InputError("fines.scaling: 'stiffness' with contact.law = linear (accepted: none or "
                       "mass with the linear law)");
    }
  }
  require(gravity >= 0 && std::isfinite(gravity), "gravity", gravity, "g >= 0 m/s^2");
  if (has(kDrag)) {
    require(finite_positive(fluid_viscosity), "fluid.viscosity", fluid_viscosity,
            "mu_f > 0 Pa s when drag is on");
  }
  if ((has(kDamping) || has(kFriction)) && !has(kHertz) && !has(kWalls)) {
    throw InputError(std::string("effects.") + effect_name(has(kDamping) ? kDamping : kFriction) +
                     ": on without a contact to act on (accepted: with effects.hertz or "
                     "effects.walls on)");
  }
}

}  // namespace powderbed::dem
