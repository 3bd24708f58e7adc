#pragma once
// What a deposition scene specifies (docs/physics.md §4): materials, fluid, gravity and the set of
// physical effects switched on. The solver composes the chosen effects once, at start.
#include <iterator>
#include <string>
#include <string_view>

namespace powderbed::dem {

// Particle material (one material for all particles). Defaults: 316L of [GZ] Table 2.
struct Material {
  double young = 193e9;    // E, Pa
  double poisson = 0.26;   // nu
  double density = 7952;   // rho, kg/m^3
  double damping = 0.1;    // zeta (0 elastic, 1 critical), particle–particle and particle–wall
  double friction = 0.1;   // mu_d, particle–particle and particle–wall
  // mu_r, rolling resistance of every contact (rolling_resistance.hpp; 0: off). Spreading runs
  // only (spread.hpp): the drop solver has no particle rotation.
  double rolling = 0;
};

struct WallMaterial {
  double young = 193e9;   // Pa
  double poisson = 0.26;
};

// The normal contact law of every particle–particle and particle–wall contact: hertz
// (hertz_normal.hpp, E* from the materials) or linear (linear_normal.hpp, one stiffness k_n for
// pairs and walls, as MFiX-DEM's default wall stiffness). Both take the damping ratio zeta.
enum class ContactLaw { hertz, linear };
// "hertz" | "linear"; throws InputError naming `option` otherwise.
ContactLaw parse_contact_law(const std::string& text, const std::string& option = "contact.law");
const char* contact_law_name(ContactLaw law);

// The friction law of every contact: sliding (sliding_friction.hpp, the regularised Coulomb law:
// no static friction, a loaded particle creeps at ~ v_reg F_t / (mu F_n)) or history
// (tangential_history.hpp: a spring capped at mu F_n, which holds a particle that is not pushed
// beyond the cap; spreading runs only, spread.hpp, since it needs particle rotation).
enum class FrictionModel { sliding, history };
FrictionModel parse_friction_model(const std::string& text,
                                   const std::string& option = "friction.model");
const char* friction_model_name(FrictionModel model);

// How the smallest particles of a wide PSD are kept from setting the time step (fines_scaling.hpp,
// docs/physics.md §4 "Fines"): none; mass (their inertial mass multiplied by (R_ref / r)^2,
// gravity and drag unchanged); stiffness (their E multiplied by (r / R_ref)^2, Hertz law only).
// Either gives every particle of radius r < R_ref the Rayleigh step of a particle of R_ref.
enum class FinesScaling { none, mass, stiffness };
// "none" | "mass" | "stiffness"; throws InputError naming `option` otherwise.
FinesScaling parse_fines_scaling(const std::string& text,
                                 const std::string& option = "fines.scaling");
const char* fines_scaling_name(FinesScaling scaling);

struct Fines {
  FinesScaling scaling = FinesScaling::none;
  double radius = 0;  // R_ref, m: particles with r < R_ref are scaled (> 0 when scaling is on)
};

// The effects of docs/architecture.md "Effects a scene calls for", one bit each: what the
// engine's contact model and its batch kernel are composed of (dem/src/contact_model.cpp,
// contact_kernel.hpp).
enum Effect : unsigned {
  kGravity = 1u << 0,
  kHertz = 1u << 1,     // particle–particle contact (Scene::law: Hertz or linear)
  kDamping = 1u << 2,   // zeta damping of every Hertz contact (particle and wall)
  kFriction = 1u << 3,  // sliding friction of every Hertz contact (particle and wall)
  kDrag = 1u << 4,      // Stokes drag
  kWalls = 1u << 5,     // Hertz contact with the box faces that are not periodic
};

// The effect list: one row per effect, in bit order. Everything that lists the effects is made
// from it: the mask of all of them, their count (the solver's dispatch table has 2^count force
// loops), their scene names (deposit's [effects] options, the decks' comments).
struct EffectRow {
  Effect bit;
  const char* name;  // in the scene's [effects] section
};
inline constexpr EffectRow kEffects[] = {
    {kGravity, "gravity"}, {kHertz, "hertz"}, {kDamping, "damping"},
    {kFriction, "friction"}, {kDrag, "drag"}, {kWalls, "walls"},
};
inline constexpr unsigned kEffectCount = std::size(kEffects);
inline constexpr unsigned kAllEffects = (1u << kEffectCount) - 1;
// Row k holds bit k, so the rows are the bits of kAllEffects, each once.
static_assert([] {
  for (unsigned k = 0; k < kEffectCount; ++k)
    if (kEffects[k].bit != 1u << k) return false;
  return true;
}(), "kEffects: row k must hold the bit 1 << k");

// Scene name of one effect bit ("gravity", "hertz", ...), "unknown" for anything else.
constexpr const char* effect_name(unsigned effect) {
  for (const EffectRow& row : kEffects)
    if (row.bit == effect) return row.name;
  return "unknown";
}
// The bit of the effect named `name` in a scene's [effects] section; 0 when none is.
constexpr unsigned effect_bit(std::string_view name) {
  for (const EffectRow& row : kEffects)
    if (name == row.name) return row.bit;
  return 0;
}

struct Scene {
  Material material;
  WallMaterial wall;
  ContactLaw law = ContactLaw::hertz;
  FrictionModel friction_model = FrictionModel::sliding;
  double stiffness = 0;  // k_n, N/m, of the linear law (pairs and walls)
  double fluid_viscosity = 2.1e-5;  // mu_f, Pa s (argon at 293 K, [GZ] Table 2)
  double gravity = 9.81;            // g, m/s^2
  unsigned effects = kAllEffects;
  Fines fines;

  bool has(unsigned effect) const { return (effects & effect) != 0; }
  // Throws InputError (naming the scene field, the value and the accepted range) for
  // non-positive E, rho, viscosity (when drag is on); nu outside [0, 0.5); zeta outside [0, 1];
  // negative mu_d, mu_r or g; damping or friction switched on with neither hertz nor walls; the
  // linear law with k_n <= 0; fines scaling with R_ref <= 0, or by stiffness with the linear law.
  void validate() const;
};

}  // namespace powderbed::dem
