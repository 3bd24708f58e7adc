// thermal's scene as Python classes (thermal/include/powderbed/thermal/scene.hpp, material.hpp,
// ray_traced_laser.hpp, scan_path.hpp): every field of a sinter scene file under the struct's
// own name. The material's numbers are the scene's (316L of [GZ] by default); material_table
// names the property table read for the run.
#include "bindings.hpp"
#include "struct_binding.hpp"

#include "powderbed/thermal/material.hpp"
#include "powderbed/thermal/ray_traced_laser.hpp"
#include "powderbed/thermal/scan_path.hpp"
#include "powderbed/thermal/scene.hpp"

namespace powderbed::python {

namespace th = thermal;

namespace {

void bind_parts(py::module_& m) {
  StructBinding<th::PhaseChange>(m, "PhaseChange", "Melting and boiling (apparent heat capacity).")
      .field("melting_point", &th::PhaseChange::melting_point, "T_m, K")
      .field("boiling_point", &th::PhaseChange::boiling_point, "T_v, K")
      .field("latent_melt", &th::PhaseChange::latent_melt, "L_m, J/kg")
      .field("latent_vapour", &th::PhaseChange::latent_vapour, "L_v, J/kg")
      .field("window", &th::PhaseChange::window, "melting window, K")
      .done();
  using R = th::RayTraceParams;
  StructBinding<R>(m, "RayTrace", "The ray-traced laser's rays (thermal/ray_traced_laser.hpp).")
      .field("rays", &R::rays, "rays per traced beam position")
      .field("cutoff", &R::cutoff, "a ray below this fraction of its power is dropped")
      .word("reflection", &R::reflection, th::kReflectionWords, "specular | diffuse | rough")
      .field("roughness", &R::roughness, "rough: rms height of the solid top, m")
      .field("wavelength", &R::wavelength, "rough: the laser's wavelength, m")
      .field("seed", &R::seed, "random seed of the rays")
      .field("max_bounces", &R::max_bounces, "a ray bouncing longer is dropped")
      .done();
  using H = th::Hatch;
  StructBinding<H>(m, "Hatch", "Parallel tracks across a region, turned per layer (scan_path.hpp).")
      .field("spacing", &H::spacing, "h between track centre lines, m")
      .field("tracks", &H::tracks, "0: as many as the region holds")
      .word("direction", &H::direction, th::kHatchDirectionWords, "one-way | alternating")
      .field("rotation", &H::rotation, "degrees per layer")
      .field("layer", &H::layer, "k: the tracks run at k x rotation from +x")
      .field("region", &H::region, "x0, x1, y0, y1, m")
      .field("power", &H::power, "W, of every track")
      .field("speed", &H::speed, "m/s, of every track")
      .done();
  // A segment has no defaults (an aggregate of six numbers): it is made whole.
  py::class_<th::ScanSegment>(m, "ScanSegment", "One straight segment of a scan path (SI).")
      .def(py::init([](double x0, double y0, double x1, double y1, double power, double speed) {
             return th::ScanSegment{x0, y0, x1, y1, power, speed};
           }),
           py::arg("x0"), py::arg("y0"), py::arg("x1"), py::arg("y1"), py::arg("power"), py::arg("speed"))
      .def_readwrite("x0", &th::ScanSegment::x0)
      .def_readwrite("y0", &th::ScanSegment::y0)
      .def_readwrite("x1", &th::ScanSegment::x1)
      .def_readwrite("y1", &th::ScanSegment::y1)
      .def_readwrite("power", &th::ScanSegment::power, "W")
      .def_readwrite("speed", &th::ScanSegment::speed, "m/s")
      .def("__repr__", [](const th::ScanSegment& s) {
        return "ScanSegment(" + std::to_string(s.x0) + ", " + std::to_string(s.y0) + ", " +
               std::to_string(s.x1) + ", " + std::to_string(s.y1) + ", power=" +
               std::to_string(s.power) + ", speed=" + std::to_string(s.speed) + ")";
      });
}

// The material, the environment and the laser.
void laser_fields(StructBinding<th::SinterScene>& b) {
  using S = th::SinterScene;
  b.field("material_table", &S::material_table, "a name of data/materials or a material file")
      .field("phase_change", &S::phase_change, "PhaseChange (or a dict of its fields)")
      .field("hold_from", &S::hold_from, "K: the solid table held from here")
      .word("liquid_conductivity", &S::liquid_conductivity, th::kLiquidConductivityWords, "solid | table")
      .field("convection", &S::convection, "h, W/m^2K")
      .field("emissivity", &S::emissivity, "eps")
      .field("environment_temperature", &S::environment_temperature, "T_env, K")
      .field("initial_temperature", &S::initial_temperature, "T0, K")
      .field("power", &S::power, "P, W")
      .field("speed", &S::speed, "v, m/s")
      .field("spot_radius", &S::spot_radius, "w, m")
      .field("absorptivity", &S::absorptivity, "alpha")
      .field("laser_y", &S::laser_y, "the track's y, m (NaN: Ly/2)")
      .field("start_x", &S::start_x, "m (NaN: one spot radius before the box)")
      .field("end_x", &S::end_x, "m (NaN: one spot radius after it)")
      .field("scan_path", &S::scan_path, "list of ScanSegment (replaces the single track)")
      .field("jump_speed", &S::jump_speed, "m/s between segments")
      .word("substrate_shading", &S::substrate_shading, th::kShadingWords, "layer | column")
      .word("absorption", &S::absorption, th::kAbsorptionWords, "ray-trace | beer-lambert")
      .field("absorptivity_liquid", &S::absorptivity_liquid, "alpha of molten surfaces (NaN: absorptivity)")
      .field("rays", &S::rays, "RayTrace (or a dict of its fields)")
      .field("retrace_interval", &S::retrace_interval, "fraction of w between traces")
      .word("optics", &S::optics, th::kOpticsWords, "fresnel | constant")
      .field("index_n_solid", &S::index_n_solid, "n of the solid")
      .field("index_k_solid", &S::index_k_solid, "k of the solid")
      .field("index_n_liquid", &S::index_n_liquid, "n of the liquid")
      .field("index_k_liquid", &S::index_k_liquid, "k of the liquid");
}

// Evaporation, wetting, the substrate, the time stepping and the effects.
void process_fields(StructBinding<th::SinterScene>& b) {
  using S = th::SinterScene;
  b.field("molar_mass", &S::molar_mass, "M of the vapour, kg/mol")
      .field("ambient_pressure", &S::ambient_pressure, "p0, Pa")
      .field("back_condensation", &S::back_condensation, "beta_r")
      .field("surface_tension", &S::surface_tension, "gamma, N/m")
      .field("contact_angle", &S::contact_angle, "wetting: degrees")
      .field("arrested_conductance", &S::arrested_conductance, "wetting: W/m^2K")
      .field("substrate_depth", &S::substrate_depth, "m")
      .field("nodes", &S::nodes, "substrate nodes along x, y, z")
      .word("substrate_periodic", &S::periodic_y, th::kSubstratePeriodicWords,
            "none | y (the plate's y sides one seam; the bed periodic along y)")
      .word("integrator", &S::integrator, th::kIntegratorWords, "explicit | implicit")
      .field("dt", &S::dt, "s; 0: the stable bound x safety")
      .field("unsafe_dt", &S::unsafe_dt, "accept dt above the explicit bound (with a warning)")
      .field("safety", &S::safety, "fraction of the stable bound")
      .field("max_particle_rise", &S::max_particle_rise, "K a particle may rise per step")
      .field("t_end", &S::t_end, "s (NaN: when the laser reaches its end)")
      .effects("effects", &S::effects, th::kSinterEffects, "the effects on, by name");
}

}  // namespace

void bind_thermal_structs(py::module_& m) {
  bind_parts(m);
  StructBinding<th::SinterScene> scene(m, "SinterScene",
                                       "A sinter scene (thermal::SinterScene): the material, "
                                       "the laser, the substrate, the time stepping, the effects.");
  laser_fields(scene);
  process_fields(scene);
  scene.done();
}

}  // namespace powderbed::python
