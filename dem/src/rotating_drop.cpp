// The drop of rotating_drop.hpp: RunSettings to SpreadSettings, SpreadSummary to RunSummary.
#include "rotating_drop.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/softening.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::dem::detail {
namespace {

void refuse_drop_only(const Scene& scene, const RunSettings& settings) {
  if (settings.until_rest || settings.lid.enabled || settings.insertion.enabled ||
      settings.integrator != Integrator::verlet || !settings.trajectory.empty()) {
    throw InputError(std::string(scene.material.rolling > 0 ? "material.rolling" : "friction.model = history") +
                     ": with --until-rest, the lid, insertion, --integrator rk4 or a trajectory "
                     "(accepted: a --t-end drop with velocity Verlet; those need the drop solver, "
                     "which has no particle rotation)");
  }
}

SpreadSettings spread_settings(const RunSettings& settings) {
  SpreadSettings s;
  s.with_tool = false;
  s.t_end = settings.t_end;
  s.young_scale = settings.young_scale;
  s.dt = settings.dt;
  s.unsafe_dt = settings.unsafe_dt;
  s.skin = settings.skin;
  s.thermo = settings.thermo;  // the drop's table: no layer, no tool
  s.thermo_every = settings.thermo_every;
  if (settings.progress) {
    s.progress = [&settings](double fraction, double kinetic_energy) {
      Progress p;
      p.time = fraction * settings.t_end;
      p.t_end = settings.t_end;
      p.kinetic_energy = kinetic_energy;
      settings.progress(p);
    };
  }
  return s;
}

}  // namespace

bool needs_rotation(const Scene& scene) {
  return scene.friction_model == FrictionModel::history || scene.material.rolling > 0;
}

RunSummary run_rotating_drop(bed::Bed& bed, const Scene& scene, const RunSettings& settings) {
  check_run_settings(settings);  // run_spread reads a negative dt as "the recommended one"
  refuse_drop_only(scene, settings);
  const SpreadSummary g = run_spread(bed, scene, spread_settings(settings));
  RunSummary r;
  r.n = bed.n();
  r.steps = g.steps;
  r.sim_time = g.sim_time;
  r.wall_time = g.wall_time;
  r.particle_steps_per_s = g.particle_steps_per_s;
  r.dt = g.dt;
  r.dt_stable = g.dt_stable;
  r.dt_limited_by = g.dt_limited_by;
  r.dt_limiting_radius = g.dt_limiting_radius;
  const Overlap overlap = max_overlap(bed, scene);  // pairs and walls, as a drop's
  r.max_overlap = overlap.relative;
  r.max_overlap_m = overlap.absolute;
  if (scene.law == ContactLaw::hertz) {
    r.max_overlap_full_stiffness = bed::hertz_overlap_of_softened(overlap.relative, settings.young_scale);
  }
  r.neighbour_rebuilds = g.neighbour_rebuilds;
  for (std::size_t i = 0; i < bed.n(); ++i) {  // physical masses, as a drop's summary
    const double v2 = bed.vx[i] * bed.vx[i] + bed.vy[i] * bed.vy[i] + bed.vz[i] * bed.vz[i];
    r.kinetic_energy += 0.5 * bed::sphere_volume(bed.radius[i]) * scene.material.density * v2;
    r.max_speed = std::max(r.max_speed, std::sqrt(v2));
  }
  return r;
}

}  // namespace powderbed::dem::detail
