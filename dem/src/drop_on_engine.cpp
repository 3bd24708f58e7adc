// The drop of drop_on_engine.hpp: the deposition driver on the engine (engine.hpp), its settle,
// rest test, snapshots and table, and the lid's side (lid_phase.hpp).
#include "drop_on_engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>

#include "box.hpp"
#include "engine.hpp"
#include "flush_subnormals.hpp"
#include "insertion.hpp"
#include "lid_phase.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/dem/time_step.hpp"
#include "powderbed/dem/trajectory.hpp"

namespace powderbed::dem::detail {
namespace {

// The engine's settings of a drop: no tool, the particles turning when a law needs it.
SpreadSettings engine_settings(const Scene& scene, const RunSettings& settings) {
  SpreadSettings s;
  s.with_tool = false;
  s.rotation = needs_rotation(scene);
  s.young_scale = settings.young_scale;
  s.dt = settings.dt;
  s.unsafe_dt = settings.unsafe_dt;
  s.skin = settings.skin;
  s.threads = settings.threads;
  s.parallel_min_particles = settings.parallel_min_particles;
  return s;
}

constexpr std::uint64_t kNever = ~std::uint64_t{0};  // no thermo row written yet

// A drop on the engine: the settle (with insertion, while the pool enters) for t_end or until
// rest, then the lid; and the engine's side of both (lid_phase.hpp's and insertion.hpp's Run).
class EngineDrop {
 public:
  // With insertion the bed passed in is the pool: it is moved aside, and the bed fills as its
  // particles enter.
  EngineDrop(bed::Bed& bed, const Scene& scene, const RunSettings& settings)
      : bed_(bed), scene_(scene), settings_(settings), spread_(engine_settings(scene, settings)),
        engine_(bed, scene, spread_) {
    if (!settings.insertion.enabled) return;
    pool_ = bed;
    for (auto* v : {&bed.x, &bed.y, &bed.z, &bed.radius, &bed.vx, &bed.vy, &bed.vz, &bed.temperature}) v->clear();
    bed.id.clear();
    bed.material.clear();
    bed.phase.clear();
  }

  RunSummary run() {
    const auto started = std::chrono::steady_clock::now();
    const FlushSubnormals flush;  // a settled bed's speeds decay into subnormals
    const TimeStepBound bound = set_up();
    const double t_end = settings_.t_end > 0 ? settings_.t_end : 1.0;  // the cap with until_rest
    const auto steps = static_cast<std::uint64_t>(std::ceil(t_end / engine_.dt - 1e-9));
    thermo_every_ = settings_.thermo_every > 0 ? settings_.thermo_every : thermo_interval(steps);
    if (!settings_.trajectory.empty()) {
      trajectory_.emplace(settings_.trajectory, bed_);
      trajectory_->write(0, 0.0, bed_);
    }
    if (settings_.thermo) thermo();
    summary_.at_rest = advance(steps, settings_.until_rest, [&] { insert_due(); }, [] { return false; });
    if (insertion_ && insertion_->active()) insertion_->end("time", time());
    if (settings_.lid.enabled && !stopped_) LidPhase<EngineDrop>(*this).run();
    engine_.sync(step_);
    if (trajectory_) {
      if (step_ % settings_.trajectory_every != 0) trajectory_->write(step_, time(), bed_);
      trajectory_->close();
    }
    if (settings_.thermo && thermo_last_ != step_) thermo();
    summarise(bound, started);
    if (settings_.progress) report(summary_.sim_time);
    return summary_;
  }

  // lid_phase.hpp's Run.
  const RunSettings& settings() const { return settings_; }
  RunSummary& summary() { return summary_; }
  bool stopped() const { return stopped_; }
  double time() const { return static_cast<double>(step_) * engine_.dt; }
  double dt() const { return engine_.dt; }
  const bed::Bed& bed() const { return bed_; }
  std::size_t count() const { return bed_.n(); }
  Box& box() { return engine_.box; }
  void set_top_velocity(double v) { engine_.top_velocity = v; }
  void keep_top(double z) { bed_.domain.upper[2] = z; }
  // The walls' candidates found anew, the lid allowed to move half the prune margin before the
  // next search (a particle moves at most as far between prunes).
  void top_reset() {
    engine_.top_slack = 0.5 * engine_.prune_margin;
    engine_.find_wall_candidates();
  }
  void top_moved() {
    if (std::abs(engine_.box.upper[2] - engine_.top_at_search) > engine_.top_slack) engine_.find_wall_candidates();
  }
  double top_force() const { return engine_.top_force(); }

  // insertion.hpp's Run (with settings(), summary(), time(), bed() above).
  const Scene& scene() const { return scene_; }
  const Box& box() const { return engine_.box; }
  const bed::Bed& pool() const { return pool_; }
  std::size_t inserted() const { return bed_.n(); }
  void place(std::size_t k, const double p[3], double vz) {
    bed_.x.push_back(p[0]);
    bed_.y.push_back(p[1]);
    bed_.z.push_back(p[2]);
    bed_.radius.push_back(pool_.radius[k]);
    bed_.id.push_back(pool_.id[k]);
    bed_.vx.push_back(0);
    bed_.vy.push_back(0);
    bed_.vz.push_back(vz);
    if (!pool_.material.empty()) bed_.material.push_back(pool_.material[k]);
    if (!pool_.temperature.empty()) bed_.temperature.push_back(pool_.temperature[k]);
    if (!pool_.phase.empty()) bed_.phase.push_back(pool_.phase[k]);
  }
  // The new particles' arrays and the neighbour list anew, every contact's history carried.
  void entered() {
    engine_.grow();
    engine_.rebuild(engine_.active());
    ++engine_.rebuilds;
  }
  void set_inserting(bool on) { inserting_ = on; }
  void end_insertion() {}  // the bed holds the particles in, the pool the rest
  void set_rest_energy(double energy) { rest_energy_ = energy; }

  // `steps` more steps: before() ahead of each, after() after it (true ends them); with
  // until_rest, until the bed has been quiet for the rest window (then true). The observer's
  // stop ends the run (stopped()).
  template <class Before, class After>
  bool advance(std::uint64_t steps, bool until_rest, Before&& before, After&& after) {
    const double progress_end = static_cast<double>(step_ + steps) * engine_.dt;
    rest_.reset();
    for (std::uint64_t s = 0; s < steps; ++s) {
      before();
      (engine_.*step_once_)(step_ + 1);
      ++step_;
      const double now = time();
      if (trajectory_ && step_ % settings_.trajectory_every == 0) {
        trajectory_->write(step_, now, engine_.whole_step_bed());
      }
      if (settings_.observer && step_ % settings_.observe_every == 0 &&
          settings_.observer(step_, now, engine_.whole_step_bed())) {
        stopped_ = true;
        return false;
      }
      if (settings_.thermo && step_ % thermo_every_ == 0) thermo();
      if (after()) return false;
      if (until_rest && !inserting_ && step_ % rest_.every() == 0 && rest_.check(step_, quiet())) return true;
      if (settings_.progress && step_ % settings_.progress_every == 0) report(progress_end);
    }
    return false;
  }

 private:
  // The engine as the spreading driver sets it up without a tool (its step from the pool's radii
  // with insertion, whose first particle enters now), and the rest test's constants.
  TimeStepBound set_up() {
    const bed::Bed& all = settings_.insertion.enabled ? pool_ : bed_;
    if (all.n() == 0) throw InputError("deposit: the bed has no particles (accepted: N >= 1)");
    engine_.box = Box::from(bed_.domain);
    engine_.set_up();
    const TimeStepBound bound = time_step_bound(all, scene_, settings_.young_scale);
    engine_.set_time_step(bound);
    if (settings_.integrator == Integrator::rk4) step_once_ = &Engine::step_rk4;
    if (settings_.insertion.enabled) {
      insertion_.emplace(*this, largest_radius(pool_));
      engine_.grow();
    }
    engine_.bound_floor();
    engine_.rebuild({});
    engine_.forces();
    const RestCriteria& rest = settings_.rest;
    double mass = 0;
    for (const double r : all.radius) mass += bed::sphere_volume(r) * scene_.material.density;
    rest_energy_ = rest.kinetic_energy > 0 ? rest.kinetic_energy : 1e-2 * 0.5 * mass * rest.max_speed * rest.max_speed;
    rest_ = RestWatch(rest, engine_.dt);
    return bound;
  }

  // Whether the bed is quiet now (RestCriteria: its kinetic energy and its fastest particle).
  bool quiet() const {
    return engine_.kinetic_energy() < rest_energy_ && engine_.max_speed() < settings_.rest.max_speed;
  }

  void insert_due() {
    if (insertion_) insertion_->insert_due();
  }

  void thermo() {
    ThermoRow row = thermo_row(bed_, scene_, bed_.n());
    row.step = step_;
    row.time = time();
    row.kinetic_energy = engine_.kinetic_energy();
    settings_.thermo(row);
    thermo_last_ = step_;
  }

  void report(double progress_end) const {
    Progress p;
    p.step = step_;
    p.time = time();
    p.t_end = progress_end;
    p.kinetic_energy = engine_.kinetic_energy();
    p.max_speed = engine_.max_speed();
    settings_.progress(p);
  }

  // The end state's summary (physical masses in the energy, pairs and walls in the overlap).
  void summarise(const TimeStepBound& bound, std::chrono::steady_clock::time_point started) {
    RunSummary& r = summary_;
    r.n = bed_.n();
    r.steps = step_;
    r.sim_time = time();
    r.dt = engine_.dt;
    r.dt_stable = bound.stable;
    r.dt_limited_by = bound.limited_by;
    r.dt_limiting_radius = bound.limiting_radius;
    r.kinetic_energy = engine_.kinetic_energy();
    r.max_speed = engine_.max_speed();
    const Overlap overlap = max_overlap(bed_, scene_);
    r.max_overlap = overlap.relative;
    r.max_overlap_m = overlap.absolute;
    r.max_overlap_full_stiffness = full_stiffness_overlap(overlap, scene_, settings_.young_scale);
    r.lost = count_outside(bed_, bed_.n());
    r.neighbour_rebuilds = engine_.rebuilds;
    r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double particle_steps = static_cast<double>(bed_.n()) * static_cast<double>(step_);
    r.particle_steps_per_s = r.wall_time > 0 ? particle_steps / r.wall_time : 0;
  }

  bed::Bed& bed_;
  const Scene& scene_;
  const RunSettings& settings_;
  SpreadSettings spread_;
  Engine engine_;
  RunSummary summary_;
  std::optional<TrajectoryWriter> trajectory_;
  bed::Bed pool_;  // with insertion: the particles to enter, in order
  std::optional<Insertion<EngineDrop>> insertion_;
  bool inserting_ = false;  // particles still enter: rest is not tested
  void (Engine::*step_once_)(std::uint64_t) = &Engine::step;  // velocity Verlet or RK4
  std::uint64_t step_ = 0;
  bool stopped_ = false;  // by the observer: no later phase runs
  double rest_energy_ = 0;  // J, RestCriteria::kinetic_energy or its default
  RestWatch rest_{RestCriteria{}, 1.0};  // set_up() sets it from the scene's step
  std::uint64_t thermo_every_ = 0, thermo_last_ = kNever;
};

}  // namespace

bool needs_rotation(const Scene& scene) {
  return scene.friction_model == FrictionModel::history || scene.material.rolling > 0;
}

void refuse_rotation_with_rk4(const Scene& scene, const RunSettings& settings) {
  if (!needs_rotation(scene) || settings.integrator != Integrator::rk4) return;
  throw InputError(std::string(scene.material.rolling > 0 ? "material.rolling" : "friction.model = history") +
                   ": with --integrator rk4 (accepted: velocity Verlet; the RK4 step has no particle "
                   "rotation and no contact history)");
}

RunSummary run_drop_on_engine(bed::Bed& bed, const Scene& scene, const RunSettings& settings) {
  return EngineDrop(bed, scene, settings).run();
}

}  // namespace powderbed::dem::detail
