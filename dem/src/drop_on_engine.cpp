// The drop of drop_on_engine.hpp: RunSettings to SpreadSettings, SpreadSummary to RunSummary.
#include "drop_on_engine.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/softening.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/dem/time_step.hpp"
#include "powderbed/dem/trajectory.hpp"

namespace powderbed::dem::detail {
namespace {

// The drop's rest test (RestCriteria, as the drop solver's: about ten checks a window, at most
// every 100 steps), its trajectory and its observer, on the engine's frames.
class DropFrames {
 public:
  DropFrames(const bed::Bed& bed, const Scene& scene, const RunSettings& settings, double dt)
      : scene_(scene), settings_(settings) {
    const RestCriteria& rest = settings.rest;
    double mass = 0;
    for (const double r : bed.radius) mass += bed::sphere_volume(r) * scene.material.density;
    rest_energy_ = rest.kinetic_energy > 0 ? rest.kinetic_energy
                                           : 1e-2 * 0.5 * mass * rest.max_speed * rest.max_speed;
    rest_every_ = static_cast<std::uint64_t>(std::clamp(std::floor(rest.window / dt / 10.0), 1.0, 100.0));
    window_steps_ = static_cast<std::uint64_t>(std::ceil(rest.window / dt));
    if (!settings.trajectory.empty()) trajectory_.emplace(settings.trajectory, bed);
  }

  // SpreadSettings::frame_every: every step that a test, a snapshot or the observer falls on.
  std::uint64_t every() const {
    const std::uint64_t rest = settings_.until_rest ? rest_every_ : 0;
    const std::uint64_t frames = trajectory_ ? settings_.trajectory_every : 0;
    const std::uint64_t observed = settings_.observer ? settings_.observe_every : 0;
    return std::gcd(std::gcd(rest, frames), observed);
  }

  // SpreadSettings::frame: true once the bed has been quiet for the window, or when the
  // observer stops the run.
  bool operator()(std::uint64_t step, double time, const bed::Bed& bed) {
    if (trajectory_ && step % settings_.trajectory_every == 0) {
      trajectory_->write(step, time, bed);
      written_ = step;
    }
    if (settings_.observer && step > 0 && step % settings_.observe_every == 0 &&
        settings_.observer(step, time, bed)) {
      return true;
    }
    if (!settings_.until_rest || step % rest_every_ != 0) return false;
    if (quiet(bed)) {
      if (quiet_since_ == kNotQuiet) quiet_since_ = step;
      at_rest_ = step - quiet_since_ >= window_steps_;
    } else {
      quiet_since_ = kNotQuiet;
    }
    return at_rest_;
  }

  // The last snapshot (unless the last step had one) and the file into place.
  void finish(std::uint64_t step, double time, const bed::Bed& bed) {
    if (!trajectory_) return;
    if (written_ != step) trajectory_->write(step, time, bed);
    trajectory_->close();
  }

  bool at_rest() const { return at_rest_; }

 private:
  static constexpr std::uint64_t kNotQuiet = ~std::uint64_t{0};

  bool quiet(const bed::Bed& bed) const {
    double energy = 0, fastest = 0;
    for (std::size_t i = 0; i < bed.n(); ++i) {
      const double v2 = bed.vx[i] * bed.vx[i] + bed.vy[i] * bed.vy[i] + bed.vz[i] * bed.vz[i];
      energy += 0.5 * bed::sphere_volume(bed.radius[i]) * scene_.material.density * v2;
      fastest = std::max(fastest, v2);
    }
    return energy < rest_energy_ && std::sqrt(fastest) < settings_.rest.max_speed;
  }

  const Scene& scene_;
  const RunSettings& settings_;
  double rest_energy_ = 0;
  std::uint64_t rest_every_ = 1, window_steps_ = 0, quiet_since_ = kNotQuiet, written_ = kNotQuiet;
  bool at_rest_ = false;
  std::optional<TrajectoryWriter> trajectory_;
};

SpreadSettings spread_settings(const Scene& scene, const RunSettings& settings, double dt) {
  SpreadSettings s;
  s.with_tool = false;
  s.rotation = needs_rotation(scene);
  s.t_end = settings.t_end > 0 ? settings.t_end : 1.0;  // the drop's cap with until_rest
  s.young_scale = settings.young_scale;
  s.dt = settings.dt;
  s.unsafe_dt = settings.unsafe_dt;
  s.skin = settings.skin;
  s.threads = settings.threads;
  s.parallel_min_particles = settings.parallel_min_particles;
  s.thermo = settings.thermo;  // the drop's table: no layer, no tool
  s.thermo_every = settings.thermo_every;
  s.progress_every = settings.progress_every;
  if (settings.progress) {
    s.progress = [&settings, dt, t_end = s.t_end](double fraction, double kinetic_energy) {
      Progress p;
      p.time = fraction * t_end;
      p.step = static_cast<std::uint64_t>(std::llround(p.time / dt));
      p.t_end = t_end;
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

bool runs_on_engine(const Scene& scene, const RunSettings&) { return needs_rotation(scene); }

void refuse_rotation_off_engine(const Scene& scene, const RunSettings& settings) {
  if (!needs_rotation(scene)) return;
  if (!settings.lid.enabled && !settings.insertion.enabled && settings.integrator == Integrator::verlet) return;
  throw InputError(std::string(scene.material.rolling > 0 ? "material.rolling" : "friction.model = history") +
                   ": with the lid, insertion or --integrator rk4 (accepted: a drop with velocity "
                   "Verlet, --t-end or --until-rest, and a trajectory; those need the drop solver, "
                   "which has no particle rotation)");
}

RunSummary run_drop_on_engine(bed::Bed& bed, const Scene& scene, const RunSettings& settings) {
  // The frames need the step: the one run_spread will take (the user's or the recommended).
  const TimeStepBound bound = time_step_bound(bed, scene, settings.young_scale);
  const double dt = settings.dt > 0 ? settings.dt : bound.recommended;
  SpreadSettings spread = spread_settings(scene, settings, dt);
  DropFrames frames(bed, scene, settings, dt);
  spread.frame_every = frames.every();
  if (spread.frame_every > 0) {
    spread.frame = [&frames](std::uint64_t step, double time, const bed::Bed& b) { return frames(step, time, b); };
  }
  const SpreadSummary g = run_spread(bed, scene, spread);
  frames.finish(g.steps, g.sim_time, bed);
  RunSummary r;
  r.at_rest = frames.at_rest();
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
  r.max_overlap_full_stiffness = full_stiffness_overlap(overlap, scene, settings.young_scale);
  r.lost = count_outside(bed, bed.n());
  r.neighbour_rebuilds = g.neighbour_rebuilds;
  for (std::size_t i = 0; i < bed.n(); ++i) {  // physical masses, as a drop's summary
    const double v2 = bed.vx[i] * bed.vx[i] + bed.vy[i] * bed.vy[i] + bed.vz[i] * bed.vz[i];
    r.kinetic_energy += 0.5 * bed::sphere_volume(bed.radius[i]) * scene.material.density * v2;
    r.max_speed = std::max(r.max_speed, std::sqrt(v2));
  }
  if (settings.progress) {  // the run's end, as the drop solver's last call
    Progress p;
    p.step = r.steps;
    p.time = p.t_end = r.sim_time;
    p.kinetic_energy = r.kinetic_energy;
    p.max_speed = r.max_speed;
    settings.progress(p);
  }
  return r;
}

}  // namespace powderbed::dem::detail
