#pragma once
// What a sinter scene specifies (docs/physics.md §5, [GZ] Table 2 defaults): material, environment,
// laser path, substrate grid, time stepping and the set of effects switched on. The solver
// composes the chosen effects once, at start.
#include <array>
#include <cmath>
#include <string>

#include "powderbed/bed/option_words.hpp"
#include "powderbed/thermal/material.hpp"
#include "powderbed/thermal/ray_traced_laser.hpp"
#include "powderbed/thermal/scan_path.hpp"

namespace powderbed::thermal {

// The effects of docs/architecture.md "Effects a scene calls for", one bit each.
enum SinterEffect : unsigned {
  kConduction = 1u << 0,          // particle–particle contact conduction
  kSubstrateContact = 1u << 1,    // particle–substrate contact conduction
  kConvection = 1u << 2,          // exposed top particles
  kRadiation = 1u << 3,           // exposed top particles
  kLaser = 1u << 4,               // laser heating of the particles
  kPenetration = 1u << 5,         // Beer–Lambert attenuation with depth (off: beta = 0)
  kLaserSubstrate = 1u << 6,      // the part of the laser that passes the powder
  kPhaseChange = 1u << 7,         // latent heats in the apparent heat capacity
  kVariableProperties = 1u << 8,  // c, k, rho from the table (off: held at T0)
  kWetting = 1u << 9,             // molten particles spread on what they touch (wetting.hpp)
  kEvaporation = 1u << 10,        // mass and energy lost by evaporation (evaporation.hpp)
  kDepression = 1u << 11,         // the vapour depression and the beam in it (vapour_depression.hpp)
};
// The list of the effects: one row each, its bit and its scene name (the option effects.NAME,
// which sinter's options are made from); the solver's kernels name the effects that shape them
// by these bits (thermal/src/effect_kernels.hpp).
struct SinterEffectRow {
  SinterEffect effect;
  const char* name;
};
inline constexpr SinterEffectRow kSinterEffects[] = {
    {kConduction, "conduction"},
    {kSubstrateContact, "substrate-contact"},
    {kConvection, "convection"},
    {kRadiation, "radiation"},
    {kLaser, "laser"},
    {kPenetration, "penetration"},
    {kLaserSubstrate, "laser-substrate"},
    {kPhaseChange, "phase-change"},
    {kVariableProperties, "variable-properties"},
    {kWetting, "wetting"},
    {kEvaporation, "evaporation"},
    {kDepression, "depression"},
};
// The effects of [GZ]'s model (wetting, evaporation and the depression go beyond it).
constexpr unsigned kAllSinterEffects = (1u << 9) - 1;
// What a melt pool at process settings needs besides (docs/sinter.md "The melt pool at process
// settings"): the default of a scene.
constexpr unsigned kProcessEffects = kWetting | kEvaporation | kDepression;

enum class Integrator { explicit_euler, implicit_euler };
inline constexpr bed::OptionWord<Integrator> kIntegratorWords[] = {
    {"explicit", Integrator::explicit_euler}, {"implicit", Integrator::implicit_euler}};

// How the laser's power is split over the bed: `beer_lambert` (docs/physics.md §5: I0 exp(-beta z) on
// each particle's projected area, Gusarov's beta, and what passes the powder onto the
// substrate) or `ray_trace` (rays on the bed's own spheres, ray_traced_laser.hpp).
enum class LaserAbsorption { beer_lambert, ray_trace };
inline constexpr bed::OptionWord<LaserAbsorption> kAbsorptionWords[] = {
    {"beer-lambert", LaserAbsorption::beer_lambert}, {"ray-trace", LaserAbsorption::ray_trace}};

// What the laser crosses before it reaches the substrate (docs/physics.md §5 writes exp(-beta H_layer)):
// `layer`: the bed's layer height everywhere; `column`: the height of the bed above each top
// node from the height map (bare spots between particles get the full beam).
enum class SubstrateShading { layer, column };
inline constexpr bed::OptionWord<SubstrateShading> kShadingWords[] = {
    {"layer", SubstrateShading::layer}, {"column", SubstrateShading::column}};

// The substrate's y sides: Dirichlet walls at T0 (`none`), or one periodic seam (`y`: the plate
// of a strip periodic across y, as a build spreads it; the bed must be periodic along y). The
// particles' network and the rays stay bounded either way (docs/sinter.md "Periodic plate").
inline constexpr bed::OptionWord<bool> kSubstratePeriodicWords[] = {{"none", false}, {"y", true}};

struct SinterScene {
  // Material ([GZ] Tables 1–2).
  std::string material_table = "316L";  // a name of data/materials or a path to a material file
  PhaseChange phase_change;
  double hold_from = 1400;  // K: solid table extrapolated to here, then held
  LiquidConductivity liquid_conductivity = LiquidConductivity::solid;
  // Environment.
  double convection = 40;             // h, W/m^2K
  double emissivity = 0.33;           // eps
  double environment_temperature = 363;  // T_env, K
  double initial_temperature = 363;   // T0 of particles and substrate, and the Dirichlet value
  // Laser along x on the line y = laser_y; NaN: the defaults of [GZ] (y = Ly/2, from one spot
  // radius before the domain to one after it).
  double power = 200;          // P, W
  double speed = 2.0;          // v, m/s
  double spot_radius = 54e-6;  // w, m
  double absorptivity = 0.33;  // alpha
  double laser_y = NAN, start_x = NAN, end_x = NAN;
  // A scan path (scan_path.hpp) replaces that single track when it is not empty: its segments'
  // ends lie on the plate, the laser is off while it jumps between them at `jump_speed`.
  std::vector<ScanSegment> scan_path;
  double jump_speed = 5;  // m/s: galvanometer scanners jump at a few m/s
  SubstrateShading substrate_shading = SubstrateShading::layer;
  LaserAbsorption absorption = LaserAbsorption::ray_trace;  // why: docs/sinter.md
  // Ray-trace only: alpha of molten surfaces (NaN: `absorptivity` in every phase), the rays,
  // and the re-trace interval: the beam is traced anew each time it moves this fraction of w,
  // and the power maps of the two traced positions around the beam are blended linearly.
  double absorptivity_liquid = NAN;
  RayTraceParams rays;
  double retrace_interval = 0.1;
  // Ray-trace only: how surfaces absorb (Fresnel from the complex refractive index n + ik of
  // each phase at the laser's wavelength, or the constant absorptivities above). 316L near
  // 1.06 µm by default (data/materials/316L.csv gives the sources).
  Optics optics = Optics::fresnel;
  double index_n_solid = 3.235, index_k_solid = 4.322, index_n_liquid = 3.235, index_k_liquid = 4.322;
  // Evaporation and the depression: molar mass M of the vapour, ambient pressure p0 (at which
  // the boiling point holds), back-condensation β_r, the liquid's surface tension γ.
  double molar_mass = 0.05585;      // kg/mol
  double ambient_pressure = 101325; // Pa
  double back_condensation = 0.18;
  double surface_tension = 1.8;     // N/m
  // Wetting only: the contact angle of the melt on molten solid, degrees, and the interfacial
  // conductance of an arrested contact (a molten particle on solid that has not remelted).
  double contact_angle = 30;
  double arrested_conductance = 1e6;  // W/m^2K
  // Substrate under the bed: x, y extents are the bed's domain; depth and node counts here.
  double substrate_depth = 0.3e-3;
  std::array<std::size_t, 3> nodes{201, 101, 61};
  bool periodic_y = false;  // kSubstratePeriodicWords
  // Time stepping: dt <= 0 means the computed stable bound times `safety`.
  Integrator integrator = Integrator::explicit_euler;
  double dt = 0;
  bool unsafe_dt = false;  // accept a dt above the explicit bound (the run may blow up)
  double safety = 0.9;
  // Accuracy limit of a particle step: the laser alone raises no particle by more than this
  // per step (K), so tiny particles under the beam subcycle instead of overshooting T_v.
  double max_particle_rise = 50;
  double t_end = NAN;          // NaN: when the laser reaches end_x (or the path's end)
  unsigned effects = kAllSinterEffects | kProcessEffects;

  bool has(unsigned effect) const { return (effects & effect) != 0; }
  // Throws InputError naming the field, the value and the accepted range.
  void validate() const;

 private:
  void validate_process_models() const;
};

}  // namespace powderbed::thermal
