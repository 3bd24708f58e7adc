// dem's scene and settings structs as Python classes (dem/include/powderbed/dem/scene.hpp,
// solver.hpp, spread.hpp, recoater.hpp): every field a user sets in a deposit or spread scene
// file, under the struct's own name. Callbacks (progress, supply) are the run functions'
// arguments, not fields.
#include "bindings.hpp"
#include "struct_binding.hpp"

#include "powderbed/dem/recoater.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::python {

namespace {

void bind_scene(py::module_& m) {
  StructBinding<dem::Material>(m, "Material", "The powder's material (default: 316L of [GZ]).")
      .field("young", &dem::Material::young, "E, Pa")
      .field("poisson", &dem::Material::poisson, "nu")
      .field("density", &dem::Material::density, "rho, kg/m^3")
      .field("damping", &dem::Material::damping, "zeta in [0, 1], pairs and walls")
      .field("friction", &dem::Material::friction, "mu_d, pairs and walls")
      .field("rolling", &dem::Material::rolling, "mu_r, rolling resistance (0: off)")
      .done();
  StructBinding<dem::WallMaterial>(m, "WallMaterial", "The walls' elastic constants.")
      .field("young", &dem::WallMaterial::young, "E, Pa")
      .field("poisson", &dem::WallMaterial::poisson, "nu")
      .done();
  StructBinding<dem::Fines>(m, "Fines", "Scaling of the finest particles (docs/deposit-fines.md).")
      .word("scaling", &dem::Fines::scaling, &dem::parse_fines_scaling, &dem::fines_scaling_name,
            "none | mass | stiffness")
      .field("radius", &dem::Fines::radius, "R_ref, m: particles below it are scaled")
      .done();
  StructBinding<dem::Scene>(m, "Scene",
                            "A DEM scene (deposit's and spread's): the powder, the walls, the "
                            "contact and friction laws, the fluid, gravity and the effects on.")
      .field("material", &dem::Scene::material, "Material (or a dict of its fields)")
      .field("wall", &dem::Scene::wall, "WallMaterial (or a dict of its fields)")
      .word("law", &dem::Scene::law, &dem::parse_contact_law, &dem::contact_law_name,
            "contact law: hertz | linear")
      .word("friction_model", &dem::Scene::friction_model, &dem::parse_friction_model,
            &dem::friction_model_name, "sliding | history")
      .field("stiffness", &dem::Scene::stiffness, "k_n of the linear law, N/m")
      .field("fluid_viscosity", &dem::Scene::fluid_viscosity, "mu_f, Pa s")
      .field("gravity", &dem::Scene::gravity, "g, m/s^2")
      .effects("effects", &dem::Scene::effects, dem::kEffects, "the effects on, by name")
      .field("fines", &dem::Scene::fines, "Fines (or a dict of its fields)")
      .done();
}

void bind_run_settings(py::module_& m) {
  StructBinding<dem::RestCriteria>(m, "RestCriteria", "When a bed is at rest (until_rest).")
      .field("max_speed", &dem::RestCriteria::max_speed, "m/s")
      .field("kinetic_energy", &dem::RestCriteria::kinetic_energy, "J; 0: from max_speed")
      .field("window", &dem::RestCriteria::window, "s of simulated time")
      .done();
  using L = dem::LidSettings;
  StructBinding<L>(m, "LidSettings", "The consolidation lid after the settle (docs/deposit-lid.md).")
      .field("enabled", &L::enabled, "lower the lid after the settle")
      .field("speed", &L::speed, "m/s")
      .field("pressure", &L::pressure, "Pa; 0: no force target")
      .field("travel", &L::travel, "m; 0: no travel limit")
      .field("depth", &L::depth, "m below the bed's surface; 0: none")
      .field("hold", &L::hold, "s")
      .field("relax", &L::relax, "s, cap on the relaxation after the release")
      .field("release", &L::release, "raise the lid after the hold")
      .done();
  using I = dem::InsertionSettings;
  StructBinding<I>(m, "InsertionSettings",
                   "Insertion from the top [KE]: the bed passed in is the pool.")
      .field("enabled", &I::enabled, "insert the bed's particles one by one")
      .field("rate", &I::rate, "particles/s")
      .field("speed", &I::speed, "m/s downward")
      .field("tries", &I::tries, "random draws per particle and insertion time")
      .field("patience", &I::patience, "s; 0: twice the fall through one diameter")
      .field("seed", &I::seed, "random seed of the positions")
      .done();
  using R = dem::RunSettings;
  StructBinding<R>(m, "RunSettings", "How a drop runs (dem::RunSettings).")
      .word("integrator", &R::integrator, dem::kIntegratorWords, "verlet | rk4")
      .field("dt", &R::dt, "s; 0: the recommended step")
      .field("unsafe_dt", &R::unsafe_dt, "accept dt above the stable bound (with a warning)")
      .field("young_scale", &R::young_scale, "E used = E / young_scale (Hertz law)")
      .field("t_end", &R::t_end, "s; with until_rest the cap (0: 1 s)")
      .field("until_rest", &R::until_rest, "stop when the bed is at rest")
      .field("rest", &R::rest, "RestCriteria (or a dict of its fields)")
      .field("skin", &R::skin, "Verlet skin, m; 0: 0.5 x the largest radius (narrowed on a narrow periodic axis)")
      .field("threads", &R::threads, "OpenMP threads; 0: OpenMP's default")
      .field("parallel_min_particles", &R::parallel_min_particles,
             "beds with fewer particles run on one thread")
      .field("trajectory", &R::trajectory, "HDF5 time series path ('': none)")
      .field("trajectory_every", &R::trajectory_every, "steps between snapshots")
      .field("progress_every", &R::progress_every, "steps between progress calls")
      .field("lid", &R::lid, "LidSettings (or a dict of its fields)")
      .field("insertion", &R::insertion, "InsertionSettings (or a dict of its fields)")
      .done();
}

void bind_spread_settings(py::module_& m) {
  using T = dem::Recoater;
  StructBinding<T>(m, "Recoater", "The recoater tool: a blade or a roller moving along +x.")
      .word("shape", &T::shape, dem::kToolShapeWords, "blade | roller")
      .field("thickness", &T::thickness, "blade: extent along x, m")
      .field("edge_radius", &T::edge_radius, "blade: radius of its bottom edges, m")
      .field("radius", &T::radius, "roller: m")
      .field("omega", &T::omega, "roller: spin about +y, rad/s")
      .field("gap", &T::gap, "lowest point above the plate, m")
      .field("speed", &T::speed, "m/s along +x")
      .field("start", &T::start, "x of the tool's centre at the start, m")
      .field("end", &T::end, "x where it stops, m")
      .field("delay", &T::delay, "s before it moves")
      .field("settle", &T::settle, "s after it stopped")
      .done();
  using Z = dem::SleepSettings;
  StructBinding<Z>(m, "SleepSettings", "Powder at rest under the tool sleeps until what moves pushes it.")
      .field("on", &Z::on, "sleep at all (default false)")
      .field("speed", &Z::speed, "at rest below this speed, m/s")
      .field("wake_speed", &Z::wake_speed, "a sleeper wakes when a particle this fast touches it, m/s")
      .field("steps", &Z::steps, "steps in a row at rest before a particle sleeps")
      .done();
  using S = dem::SpreadSettings;
  StructBinding<S>(m, "SpreadSettings", "How a spread runs (dem::SpreadSettings).")
      .field("tool", &S::tool, "Recoater (or a dict of its fields)")
      .field("with_tool", &S::with_tool, "false: a granular run of t_end without tool or supply")
      .field("rotation", &S::rotation,
             "false: particles do not turn (no history friction or rolling then)")
      .field("supply_x0", &S::supply_x0, "supply region's start along x, m")
      .field("supply_x1", &S::supply_x1, "supply region's end along x, m")
      .field("supply_height", &S::supply_height, "supply region's height, m")
      .field("platform_edge", &S::platform_edge,
             "the dosing platform's edge along x, m (None: no platform; the floor at x <= edge "
             "stands at the tool's bottom)")
      .field("layers", &S::layers, "layers to spread")
      .field("remove_overflow", &S::remove_overflow, "remove the powder pushed past the tool's end")
      .field("chamber", &S::chamber, "overflow: keep what lies under the tool's bottom")
      .field("layer_thickness", &S::layer_thickness, "plate drop between layers, m")
      .field("freeze_depth", &S::freeze_depth, "freeze powder this far below the tool, m (0: off)")
      .field("sleep", &S::sleep, "SleepSettings (or a dict of its fields)")
      .field("until_rest", &S::until_rest,
             "after the tool's settle, settle each layer on until the powder behind it rests")
      .field("rest", &S::rest, "RestCriteria of until_rest (or a dict of its fields)")
      .field("rest_cap", &S::rest_cap, "until_rest: the most a layer settles, s")
      .field("young_scale", &S::young_scale, "E used = E / young_scale")
      .field("dt", &S::dt, "s; 0: 0.2 x the Rayleigh step")
      .field("unsafe_dt", &S::unsafe_dt, "accept dt above the stable bound (with a warning)")
      .field("skin", &S::skin, "m; 0: 0.5 x the largest radius")
      .field("t_end", &S::t_end, "without tool: simulated time, s")
      .field("gravity_tilt", &S::gravity_tilt, "gravity tilted about +y, rad")
      .field("threads", &S::threads, "OpenMP threads; 0: OpenMP's default")
      .field("parallel_min_particles", &S::parallel_min_particles,
             "beds with fewer particles run on one thread")
      .field("progress_every", &S::progress_every, "steps between progress calls")
      .done();
  // What a spread leaves for the next call (spread(..., state=...)): opaque but for its counts.
  py::class_<dem::SpreadState>(m, "SpreadState",
                               "A spread's state at its end: pass it to the next spread of the "
                               "bed it returned to continue bit for bit.")
      .def_readonly("layers_done", &dem::SpreadState::layers_done)
      .def_readonly("step", &dem::SpreadState::step)
      .def_readonly("time", &dem::SpreadState::time, "s")
      .def_readonly("tool_x", &dem::SpreadState::tool_x, "m")
      .def_readonly("plate_offset", &dem::SpreadState::plate_offset, "m");
}

}  // namespace

void bind_dem_structs(py::module_& m) {
  bind_scene(m);
  bind_run_settings(m);
  bind_spread_settings(m);
}

}  // namespace powderbed::python
