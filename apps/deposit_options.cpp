// deposit's options and the DEM scene they make: shared by deposit and build, which reads a
// deposit recoater scene for each layer's spread.
#include "common/thermo_table.hpp"
#include "deposit_options.hpp"

#include <string>

#include <fmt/format.h>

#include "common/deck_export.hpp"
#include "common/material_options.hpp"
#include "common/progress.hpp"
#include "common/threads.hpp"
#include "deposit_spread.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/solver.hpp"

namespace powderbed::app {

namespace {

// Where the particles come from: a bed, a PSD placed in the box, or the insertion's pool.
void add_source_options(po::options_description& desc, dem::InsertionSettings& insertion) {
  desc.add_options()
      ("in", po::value<std::string>(), "start from this bed (HDF5, CSV needs --domain)")
      ("psd", po::value<std::string>(), "particle size distribution (see bed/psd.hpp syntax), m")
      ("count", po::value<std::size_t>(), "number of particles to insert from --psd")
      ("domain", po::value<std::string>(), "box LX,LY,LZ (m), floor at z = 0")
      ("periodic", po::value<std::string>()->default_value("none"),
       "periodic axes: none, x, y or x,y (a spread, recoater.tool: y unless given)")
      ("insert-z", po::value<std::string>(), "insertion region Z0,Z1 (m); default: the whole box")
      ("insert.enabled", po::value<bool>()->default_value(false),
       "insertion from the top (Kumar Yadav & Eshraghi 2016): the --count particles of --psd "
       "enter one by one at random positions in the top layer of the box (one diameter), "
       "moving down, until the box is full; the rest of them are dropped")
      ("insert.rate", po::value<double>(&insertion.rate)->default_value(insertion.rate),
       "insertion: particles per second")
      ("insert.speed", po::value<double>(&insertion.speed)->default_value(insertion.speed),
       "insertion: initial downward speed (m/s)")
      ("insert.tries", po::value<std::size_t>(&insertion.tries)->default_value(insertion.tries),
       "insertion: random draws for a free spot per particle and insertion time")
      ("insert.patience", po::value<double>(&insertion.patience)->default_value(insertion.patience),
       "insertion: the box is full once no particle has found a free spot for this long (s; 0: "
       "twice the time to fall one diameter)");
}

// How long and how the drop runs, and what it writes.
void add_run_options(po::options_description& desc, dem::RunSettings& run, dem::Scene& scene) {
  desc.add_options()
      ("t-end", po::value<double>(&run.t_end),
       "simulated time (s); with --until-rest the cap (default 1 s)")
      ("until-rest", po::bool_switch(&run.until_rest),
       "stop when the bed is at rest (rest.speed, rest.window)")
      ("rest.speed", po::value<double>(&run.rest.max_speed)->default_value(run.rest.max_speed),
       "rest: largest speed below this (m/s)")
      ("rest.window", po::value<double>(&run.rest.window)->default_value(run.rest.window),
       "rest: for this long (s of simulated time)")
      ("dt", po::value<double>(), "time step (s); default (and 0): 0.2 x the Rayleigh step of the "
                                  "smallest particle (linear law: 0.2 x 1/omega_0 = sqrt(m*/k_n) of "
                                  "its pair), or the drag relaxation time when shorter")
      ("unsafe-dt", po::bool_switch(), "accept a --dt above the stable bound (with a warning)")
      ("integrator", po::value<std::string>()->default_value("verlet"), "verlet or rk4")
      ("young-scale", po::value<double>()->default_value(1.0),
       "stiffness softening S of the Hertz law: E used = E / S (particles and walls)")
      ("contact.law", po::value<std::string>()->default_value("hertz"),
       "normal contact law of pairs and walls: hertz (from E, nu; softened by young-scale) or "
       "linear (spring-dashpot F = k_n delta + c delta', contact.stiffness; the law of "
       "Kumar Yadav & Eshraghi 2016's MFiX beds)")
      ("contact.stiffness", po::value<double>(&scene.stiffness), "k_n of the linear law (N/m)")
      ("seed", po::value<std::uint64_t>(), "random seed (insertion positions and sizes)")
      ("out", po::value<std::string>(), "output bed (HDF5 + XDMF sidecar)")
      ("allow-lost", po::value<std::size_t>()->default_value(0),
       "particles that may leave the box during the run (more: exit 3, nothing written)")
      ("trust-units", po::bool_switch(),
       "skip the guard against unit slips (a Young's modulus below 1 MPa: GPa typed as Pa?)")
      ("trajectory", po::value<std::string>(), "HDF5 time series of snapshots (+ .xmf)")
      ("export-deck", po::value<std::string>(),
       "also write the settled bed as a LAMMPS data file and a lammps or liggghts input deck with "
       "this run's laws beside --out: BED.data, in.BED.<engine> (docs/decks.md); with "
       "recoater.tool (liggghts only) the spread's deck instead of the spread: the first "
       "layer's supply, the tool as BED.tool.stl and the layer loop")
      ("every", po::value<std::uint64_t>()->default_value(0), "steps between snapshots");
}

// The scene's material, walls, fluid and gravity (the effects: add_deposit_options).
void add_scene_options(po::options_description& desc, dem::Scene& s) {
  dem::Material& m = s.material;
  desc.add_options()
      ("material.young", po::value<double>(&m.young)->default_value(m.young), "E (Pa)")
      ("material.poisson", po::value<double>(&m.poisson)->default_value(m.poisson), "nu")
      ("material.density", po::value<double>(&m.density)->default_value(m.density),
       "rho (kg/m^3)")
      ("material.damping", po::value<double>(&m.damping)->default_value(m.damping),
       "damping ratio zeta in [0, 1]")
      ("material.friction", po::value<double>(&m.friction)->default_value(m.friction),
       "sliding friction mu_d")
      ("fluid.viscosity", po::value<double>(&s.fluid_viscosity)->default_value(s.fluid_viscosity),
       "mu_f (Pa s)")
      ("wall.young", po::value<double>(&s.wall.young)->default_value(s.wall.young), "wall E (Pa)")
      ("wall.poisson", po::value<double>(&s.wall.poisson)->default_value(s.wall.poisson),
       "wall nu")
      ("gravity", po::value<double>(&s.gravity)->default_value(s.gravity), "g (m/s^2)")
      ("fines.scaling", po::value<std::string>()->default_value("none"),
       "keep the smallest particles from setting the time step: none, mass (their "
       "inertial mass x (R_ref/r)^2; gravity and drag unchanged) or stiffness (their E x "
       "(r/R_ref)^2, Hertz law); docs/deposit-fines.md")
      ("fines.radius", po::value<double>(&s.fines.radius)->default_value(s.fines.radius),
       "R_ref (m): particles of radius below it get the Rayleigh step of a particle of R_ref");
}

// The lid's consolidation after the settle (dem::LidSettings).
void add_lid_options(po::options_description& desc, dem::LidSettings& l) {
  desc.add_options()
      ("lid", po::bool_switch(), "consolidate the settled bed with the lid (as lid.enabled)")
      ("lid.enabled", po::value<bool>()->default_value(false),
       "lid: after the settle, lower the box's top wall onto the bed, hold it, release it")
      ("lid.speed", po::value<double>(&l.speed)->default_value(l.speed),
       "lid: lowering speed (m/s)")
      ("lid.pressure", po::value<double>(&l.pressure)->default_value(l.pressure),
       "lid: stop lowering when the bed pushes on it with this pressure (Pa; 0: no target)")
      ("lid.travel", po::value<double>(&l.travel)->default_value(l.travel),
       "lid: stop lowering after this travel from the highest particle top (m; 0: no limit)")
      ("lid.depth", po::value<double>(&l.depth)->default_value(l.depth),
       "lid: instead of a travel, lower it to this depth below the bed's surface (the 90th "
       "percentile of the particle tops), overlapping the top layer by it (m; 0: none)")
      ("lid.hold", po::value<double>(&l.hold)->default_value(l.hold), "lid: time held in place (s)")
      ("lid.release", po::value<bool>(&l.release)->default_value(l.release),
       "lid: true releases it after the hold; false keeps it as the bed's top face (the bed's "
       "domain ends at the lid, for keff's hot wall)")
      ("lid.relax", po::value<double>(&l.relax)->default_value(l.relax),
       "lid: cap on the relaxation after the release (s; it ends earlier at rest)");
}

// What is measured on and done to the settled bed before it is written.
void add_result_options(po::options_description& desc) {
  desc.add_options()
      ("crop-top", po::value<bool>()->default_value(false),
       "write the bed with the box's top at the highest particle top (z + r), so that a top "
       "wall touches the bed (keff's wall)")
      ("core-margin", po::value<double>(),
       "core density: margin from the floor, side walls and surface (m); default 2 mean "
       "diameters");
}

}  // namespace

void add_deposit_options(po::options_description& desc, DepositOptions& bound) {
  add_common_options(desc);
  add_threads_option(desc);
  add_progress_option(desc);
  add_thermo_options(desc);
  add_material_options(desc, "deposit");
  add_source_options(desc, bound.run.insertion);
  add_run_options(desc, bound.run, bound.scene);
  add_scene_options(desc, bound.scene);
  add_lid_options(desc, bound.run.lid);
  add_result_options(desc);
  add_spread_options(desc, bound.spread, bound.scene);
  for (const dem::EffectRow& effect : dem::kEffects) {
    const std::string name = fmt::format("effects.{}", effect.name);
    desc.add_options()(name.c_str(), po::value<bool>()->default_value(true),
                       "effect on/off (true/false)");
  }
}

std::span<const bed::UnitEntry> deposit_units() {
  static constexpr bed::UnitEntry kUnits[] = {
      // the run (dem::write_run_json, write_spread_json; write_contact_laws)
      {"n", "1"}, {"steps", "1"}, {"sim_time", "s"}, {"wall_time", "s"},
      {"particle_steps_per_s", "1/s"}, {"dt", "s"}, {"dt_stable", "s"}, {"young_scale", "1"},
      // a drop
      {"dt_limiting_radius", "m"}, {"fines_radius", "m"}, {"stiffness", "N/m"},
      {"kinetic_energy", "J"}, {"max_speed", "m/s"}, {"max_overlap", "1"},
      {"max_overlap_m", "m"}, {"max_overlap_full_stiffness", "1"}, {"lost", "1"},
      {"neighbour_rebuilds", "1"}, {"core_density", "1"}, {"core_margin", "m"},
      {"domain_top", "m"}, {"inserted", "1"}, {"end_time", "s"},
      // the lid
      {"start_z", "m"}, {"stop_z", "m"}, {"surface_z", "m"}, {"travel", "m"},
      {"target_force", "N"}, {"stop_force", "N"}, {"max_force", "N"}, {"hold_end_force", "N"},
      {"hold_end_z", "m"}, {"hold_late_force", "N"}, {"release_time", "s"},
      // a spread and its layers
      {"rolling", "1"}, {"layers_done", "1"}, {"layer", "1"}, {"supplied", "1"},
      {"tool_bottom", "m"}, {"max_tool_force", "N"}, {"mean_tool_force_x", "N"},
      {"density_under_gap", "1"}, {"overflow", "1"}, {"under_platform", "1"}, {"frozen", "1"}, {"frozen_tool_contacts", "1"},
      {"asleep", "1"}, {"sleep_changes", "1"}, {"settle_time", "s"},
  };
  return kUnits;
}

void write_contact_laws(bed::JsonWriter& j, double young_scale, const dem::Scene& scene) {
  j.value("young_scale", young_scale)
      .value("contact_law", dem::contact_law_name(scene.law))
      .value("friction_model", dem::friction_model_name(scene.friction_model));
}

dem::Scene deposit_scene(const po::variables_map& vm, const dem::Scene& bound) {
  dem::Scene scene = bound;
  if (!vm["trust-units"].as<bool>() && scene.material.young < 1e6) {
    throw InputError(fmt::format("material.young: {:g} Pa is below the 1 MPa of the softest "
                                 "powders: a unit slip? (accepted: E in Pa, e.g. 193e9 for 193 "
                                 "GPa; --trust-units if it is meant)",
                                 scene.material.young));
  }
  scene.friction_model = dem::parse_friction_model(vm["friction.model"].as<std::string>());
  scene.law = dem::parse_contact_law(vm["contact.law"].as<std::string>());
  scene.fines.scaling = dem::parse_fines_scaling(vm["fines.scaling"].as<std::string>());
  if (vm.count("contact.stiffness")) {
    if (scene.law != dem::ContactLaw::linear)
      throw InputError("contact.stiffness: given with contact.law = hertz (accepted: with "
                       "contact.law = linear)");
  } else if (scene.law == dem::ContactLaw::linear) {
    throw InputError("contact.stiffness: missing with contact.law = linear (accepted: k_n > 0 N/m)");
  }
  scene.effects = 0;
  for (const dem::EffectRow& effect : dem::kEffects) {
    if (vm[fmt::format("effects.{}", effect.name)].as<bool>()) scene.effects |= effect.bit;
  }
  return scene;
}
}  // namespace powderbed::app
