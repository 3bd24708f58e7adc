// The deposition run of docs/physics.md §4: set-up, the once-only dispatch to a loop specialised for the
// scene's effects, velocity Verlet and classic RK4 steps, rest detection, snapshots.
// Over 600 lines because the drop's engine and its drivers (insertion, the lid) share this file
// until they become the one engine's drivers (issue 33; tests/dem/test_engines.cpp holds the
// two engines to one another meanwhile).
#include "powderbed/dem/solver.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>
#include <utility>

#include "flush_subnormals.hpp"
#include "forces.hpp"
#include "parallel.hpp"
#include "drop_on_engine.hpp"
#include "drop_solver.hpp"
#include "insertion.hpp"
#include "lid_phase.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/softening.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/dem/contact_moduli.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/fines_scaling.hpp"
#include "powderbed/dem/stokes_drag.hpp"
#include "powderbed/dem/time_step.hpp"
#include "powderbed/dem/trajectory.hpp"

namespace powderbed::dem {

Integrator parse_integrator(const std::string& text, const std::string& option) {
  return bed::parse_word(text, option, kIntegratorWords, "an integrator");
}

std::size_t remove_lost_particles(bed::Bed& bed) {
  const detail::Box box = detail::Box::from(bed.domain);
  std::size_t kept = 0;
  const bool vel = bed.has_velocity();
  const bool mat = !bed.material.empty(), temp = !bed.temperature.empty(),
             phase = !bed.phase.empty();
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double p[3] = {bed.x[i], bed.y[i], bed.z[i]};
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      inside = inside && (box.periodic[a] || (p[a] >= box.lower[a] && p[a] <= box.upper[a]));
    }
    if (!inside) continue;
    bed.x[kept] = bed.x[i];
    bed.y[kept] = bed.y[i];
    bed.z[kept] = bed.z[i];
    bed.radius[kept] = bed.radius[i];
    bed.id[kept] = bed.id[i];
    if (vel) {
      bed.vx[kept] = bed.vx[i];
      bed.vy[kept] = bed.vy[i];
      bed.vz[kept] = bed.vz[i];
    }
    if (mat) bed.material[kept] = bed.material[i];
    if (temp) bed.temperature[kept] = bed.temperature[i];
    if (phase) bed.phase[kept] = bed.phase[i];
    ++kept;
  }
  const std::size_t removed = bed.n() - kept;
  for (auto* v : {&bed.x, &bed.y, &bed.z, &bed.radius}) v->resize(kept);
  bed.id.resize(kept);
  if (vel) {
    bed.vx.resize(kept);
    bed.vy.resize(kept);
    bed.vz.resize(kept);
  }
  if (mat) bed.material.resize(kept);
  if (temp) bed.temperature.resize(kept);
  if (phase) bed.phase.resize(kept);
  return removed;
}

namespace {

using detail::Box;
using detail::ContactTables;
using detail::ForceArrays;
using detail::ForceParams;
using detail::NeighbourList;
using detail::ParticleView;

// The force loop compiled for one effect mask and law (forces.hpp compute_forces<E, Law>).
using ForcesFn = void (*)(const ForceArrays&, const ForceParams&, const NeighbourList&,
                          ContactTables&, int);

// Everything one run owns; the bed's own x, y, z, vx, vy, vz arrays are the state.
struct Context {
  Context(bed::Bed& b, const RunSettings& s) : bed(b), settings(s) {}
  bed::Bed& bed;
  const RunSettings& settings;
  std::size_t n = 0;
  int threads = 1;
  double dt = 0;
  ForceParams params;
  // mass: inertial (scaled for fines under mass scaling); weight: physical (gravity, energy);
  // young: per-particle E under stiffness scaling (empty otherwise).
  std::vector<double> mass, inv_mass, weight, young, drag, fx, fy, fz;
  // RK4: state at the start of the step and the weighted sums of the stage derivatives.
  std::vector<double> x0, y0, z0, u0, v0, w0, sx, sy, sz, su, sv, sw;
  NeighbourList list;
  ContactTables tables;
  // The law's tabulation (tabulate_contacts<Law>) and the scene's force loop, chosen once at
  // start (force_loop): the steps below are plain functions that call it once per force
  // evaluation, so an effect that is off is absent from the loop over contacts, not tested in it.
  void (*tabulate)(ContactTables&, const ForceArrays&, const ForceParams&, const NeighbourList&,
                   double, int) = nullptr;
  ForcesFn forces = nullptr;
  std::uint64_t rebuilds = 0;

  ParticleView view() const { return {bed.x.data(), bed.y.data(), bed.z.data(), bed.radius.data(), n}; }
  ForceArrays arrays() {
    return {bed.x.data(),  bed.y.data(),  bed.z.data(),      bed.vx.data(),
            bed.vy.data(), bed.vz.data(), bed.radius.data(), mass.data(),
            weight.data(), drag.data(),   young.empty() ? nullptr : young.data(),
            fx.data(),     fy.data(),     fz.data(),         n};
  }
  void rebuild() {
    list.build(view(), threads, threads > 1);
    tabulate(tables, arrays(), params, list, list.skin(), threads);
  }
  void compute_forces() { forces(arrays(), params, list, tables, threads); }
  void rebuild_if_needed() {
    if (list.moved_more_than(view(), 0.5 * list.skin(), threads)) {
      rebuild();
      ++rebuilds;
    }
  }
};

// True when every value is finite: a branch-free test of the 11 exponent bits (all ones for
// inf and NaN: adding 1 carries into bit 11), shifts, masks and adds that the compiler
// vectorises even with SSE2's lack of 64-bit compares; cheap enough for every step.
bool all_finite(const std::vector<double>& values) {
  std::uint64_t bad = 0;
  for (const double v : values) bad |= (((std::bit_cast<std::uint64_t>(v) >> 52) & 0x7ffu) + 1) >> 11;
  return bad == 0;
}

// A vectorised test of the velocities first, then (only on failure) a serial scan so that the
// first bad particle is reported. Velocities suffice: positions are sums of finite positions
// and dt times velocities, so a non-finite position needs a non-finite (or ~1e300 m/s)
// velocity, which this or the next step's test catches.
void check_finite(const Context& c, std::uint64_t step) {
  const bed::Bed& b = c.bed;
  if (all_finite(b.vx) && all_finite(b.vy) && all_finite(b.vz)) return;
  for (std::size_t i = 0; i < c.n; ++i) {
    if (std::isfinite(b.x[i] + b.y[i] + b.z[i] + b.vx[i] + b.vy[i] + b.vz[i])) continue;
    throw NumericalError(fmt::format(
        "particle id {} (index {}) has a non-finite position or velocity at step {} (t = {:g} "
        "s); try a smaller --dt",
        b.id[i], i, step, static_cast<double>(step) * c.dt));
  }
}

// v += h F / m and x += dt v on particles [begin, end) of one axis: restrict-qualified plain
// loops that the compiler vectorises.
void kick(std::size_t begin, std::size_t end, double h, const double* __restrict f,
          const double* __restrict inv_mass, double* __restrict v) {
  for (std::size_t i = begin; i < end; ++i) v[i] += h * f[i] * inv_mass[i];
}
void drift(std::size_t begin, std::size_t end, double dt, const double* __restrict v,
           double* __restrict x) {
  for (std::size_t i = begin; i < end; ++i) x[i] += dt * v[i];
}

// Velocity Verlet (kick–drift–kick); velocity-dependent forces see the half-step velocity.
void step_verlet(Context& c, std::uint64_t step) {
  const double dt = c.dt, half = 0.5 * c.dt;
  bed::Bed& b = c.bed;
  const Box& box = c.params.box;
  const auto kick_all = [&](std::size_t begin, std::size_t end) {
    kick(begin, end, half, c.fx.data(), c.inv_mass.data(), b.vx.data());
    kick(begin, end, half, c.fy.data(), c.inv_mass.data(), b.vy.data());
    kick(begin, end, half, c.fz.data(), c.inv_mass.data(), b.vz.data());
  };
  detail::for_each_chunk(c.n, c.threads, [&](std::size_t begin, std::size_t end) {
    kick_all(begin, end);
    drift(begin, end, dt, b.vx.data(), b.x.data());
    drift(begin, end, dt, b.vy.data(), b.y.data());
    drift(begin, end, dt, b.vz.data(), b.z.data());
    if (!box.any_periodic()) return;
    for (std::size_t i = begin; i < end; ++i) {
      b.x[i] = box.wrap(0, b.x[i]);
      b.y[i] = box.wrap(1, b.y[i]);
      b.z[i] = box.wrap(2, b.z[i]);
    }
  });
  c.rebuild_if_needed();
  c.compute_forces();
  detail::for_each_chunk(c.n, c.threads, kick_all);
  check_finite(c, step);
}

// Classic RK4 on (x, v) ([GZ]); four force evaluations per step on the same neighbour list
// (stage positions stay within one step's travel, well inside the skin).
void step_rk4(Context& c, std::uint64_t step) {
  const double dt = c.dt;
  bed::Bed& b = c.bed;
  const Box& box = c.params.box;
  c.rebuild_if_needed();
  detail::for_each_particle(c.n, c.threads, [&](std::size_t i) {
    c.x0[i] = b.x[i];
    c.y0[i] = b.y[i];
    c.z0[i] = b.z[i];
    c.u0[i] = b.vx[i];
    c.v0[i] = b.vy[i];
    c.w0[i] = b.vz[i];
  });
  // Stage k: derivative (v, F/m) at the current stage state in the bed arrays; weights 1,2,2,1.
  for (int stage = 0; stage < 4; ++stage) {
    c.compute_forces();
    const double weight = (stage == 0 || stage == 3) ? 1.0 : 2.0;
    const double next = stage < 2 ? 0.5 * dt : dt;  // offset of the next stage
    detail::for_each_particle(c.n, c.threads, [&](std::size_t i) {
      const double ax = c.fx[i] * c.inv_mass[i], ay = c.fy[i] * c.inv_mass[i],
                   az = c.fz[i] * c.inv_mass[i];
      if (stage == 0) {
        c.sx[i] = b.vx[i];
        c.sy[i] = b.vy[i];
        c.sz[i] = b.vz[i];
        c.su[i] = ax;
        c.sv[i] = ay;
        c.sw[i] = az;
      } else {
        c.sx[i] += weight * b.vx[i];
        c.sy[i] += weight * b.vy[i];
        c.sz[i] += weight * b.vz[i];
        c.su[i] += weight * ax;
        c.sv[i] += weight * ay;
        c.sw[i] += weight * az;
      }
      if (stage < 3) {
        b.x[i] = c.x0[i] + next * b.vx[i];
        b.y[i] = c.y0[i] + next * b.vy[i];
        b.z[i] = c.z0[i] + next * b.vz[i];
        b.vx[i] = c.u0[i] + next * ax;
        b.vy[i] = c.v0[i] + next * ay;
        b.vz[i] = c.w0[i] + next * az;
      }
    });
  }
  const double sixth = dt / 6.0;
  detail::for_each_particle(c.n, c.threads, [&](std::size_t i) {
    b.x[i] = box.wrap(0, c.x0[i] + sixth * c.sx[i]);
    b.y[i] = box.wrap(1, c.y0[i] + sixth * c.sy[i]);
    b.z[i] = box.wrap(2, c.z0[i] + sixth * c.sz[i]);
    b.vx[i] = c.u0[i] + sixth * c.su[i];
    b.vy[i] = c.v0[i] + sixth * c.sv[i];
    b.vz[i] = c.w0[i] + sixth * c.sw[i];
  });
  check_finite(c, step);
}

// Force (N) of the bed on the lid (the box's top face): the wall law of forces.hpp's wall_face,
// summed over the particles the face tables list near it.
template <class Law>
double lid_force(const Context& c, bool damping) {
  double total = 0;
  const double top = c.params.box.upper[2];
  for (const std::uint32_t i : c.tables.face_particles[5]) {
    const double delta = c.bed.radius[i] - (top - c.bed.z[i]);
    if (delta <= 0) continue;
    const detail::NormalConstants& k = c.tables.wall[i];
    total += damping ? Law::damped(k.elastic, k.damping, delta, c.bed.vz[i] - c.params.top_velocity)
                     : Law::elastic(k.elastic, delta);
  }
  return total;
}

// The once-only dispatch: a table of the force loops of every effect set (scene.hpp kEffects),
// per law. Only the force loop is compiled per set: the integrators around it are the same code
// for every set (instantiating them per set doubled this file's compile time for nothing).
template <class Law, std::size_t... Masks>
ForcesFn force_loop(unsigned effects, std::index_sequence<Masks...>) {
  static constexpr std::array<ForcesFn, sizeof...(Masks)> table{
      &detail::compute_forces<static_cast<unsigned>(Masks), Law>...};
  return table[effects];
}

// Serial sums, so that the rest test (and hence the run length) cannot depend on threads.
void kinetic_state(const Context& c, double& energy, double& max_speed) {
  energy = 0;
  double max2 = 0;
  for (std::size_t i = 0; i < c.n; ++i) {
    const double v2 =
        c.bed.vx[i] * c.bed.vx[i] + c.bed.vy[i] * c.bed.vy[i] + c.bed.vz[i] * c.bed.vz[i];
    energy += 0.5 * c.weight[i] * v2;
    max2 = std::max(max2, v2);
  }
  max_speed = std::sqrt(max2);
}

void check_bed(const bed::Bed& bed) {
  if (bed.domain.dimension != 3) {
    throw InputError("deposit: the bed is 2D (accepted: 3D beds only)");
  }
  if (bed.domain.periodic[2]) {
    throw InputError("--periodic: z cannot be periodic (accepted: x, y; gravity acts along z)");
  }
  const double lo[3] = {bed.domain.lower[0], bed.domain.lower[1], bed.domain.lower[2]};
  const double hi[3] = {bed.domain.upper[0], bed.domain.upper[1], bed.domain.upper[2]};
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double p[3] = {bed.x[i], bed.y[i], bed.z[i]};
    for (int a = 0; a < 3; ++a) {
      if (p[a] < lo[a] || p[a] > hi[a]) {
        throw InputError(fmt::format(
            "--in: particle id {} has {} = {:g} outside the domain [{:g}, {:g}] (accepted: every "
            "centre inside the domain)",
            bed.id[i], "xyz"[a], p[a], lo[a], hi[a]));
      }
    }
  }
}

void check_insertion(const InsertionSettings& ins, const RunSettings& s, const Scene& scene) {
  if (!ins.enabled) return;
  const auto require = require_in_range;  // bed/errors.hpp
  const auto finite = [](double v) { return std::isfinite(v); };
  require(finite(ins.rate) && ins.rate > 0, "insert.rate", ins.rate, "rate > 0 particles/s");
  require(finite(ins.speed) && ins.speed >= 0, "insert.speed", ins.speed, "speed >= 0 m/s");
  require(ins.tries >= 1, "insert.tries", static_cast<double>(ins.tries), "tries >= 1");
  require(finite(ins.patience) && ins.patience >= 0, "insert.patience", ins.patience,
          "patience >= 0 s");
  if (ins.patience == 0 && ins.speed == 0 && !(scene.has(kGravity) && scene.gravity > 0)) {
    throw InputError("insert.patience: 0 with neither an insertion speed nor gravity (accepted: "
                     "a patience > 0 s, an insert.speed > 0 or gravity)");
  }
  if (!s.trajectory.empty()) {
    throw InputError("--trajectory: with insertion (accepted: one or the other; the snapshots "
                     "have a fixed particle count)");
  }
}

void check_lid(const LidSettings& lid, const Scene& scene) {
  if (!lid.enabled) return;
  const auto require = require_in_range;  // bed/errors.hpp
  const auto finite = [](double v) { return std::isfinite(v); };
  require(finite(lid.speed) && lid.speed > 0, "lid.speed", lid.speed, "speed > 0 m/s");
  require(finite(lid.pressure) && lid.pressure >= 0, "lid.pressure", lid.pressure, "P >= 0 Pa");
  require(finite(lid.travel) && lid.travel >= 0, "lid.travel", lid.travel, "travel >= 0 m");
  require(finite(lid.hold) && lid.hold >= 0, "lid.hold", lid.hold, "hold >= 0 s");
  require(finite(lid.relax) && lid.relax >= 0, "lid.relax", lid.relax, "relax >= 0 s");
  require(finite(lid.depth) && lid.depth >= 0, "lid.depth", lid.depth, "depth >= 0 m");
  if (lid.depth > 0 && lid.travel > 0) {
    throw InputError("lid.depth / lid.travel: both set (accepted: one of them)");
  }
  if (!(lid.pressure > 0 || lid.travel > 0 || lid.depth > 0)) {
    throw InputError("lid.pressure / lid.travel / lid.depth: none set (accepted: a pressure > 0 "
                     "Pa, a travel or depth > 0 m, or a pressure with one of them)");
  }
  if (!scene.has(kWalls)) {
    throw InputError("lid: on with effects.walls off (accepted: the lid is the box's top wall; "
                     "turn effects.walls on)");
  }
}

// Everything run_deposition refuses, before any work.
void check_run(const bed::Bed& bed, const Scene& scene, const RunSettings& settings) {
  scene.validate();
  detail::refuse_rotation_with_rk4(scene, settings);
  bed.validate("deposit input bed");
  check_bed(bed);
  check_run_settings(settings);
  check_lid(settings.lid, scene);
  check_insertion(settings.insertion, settings, scene);
  if (scene.law == ContactLaw::linear && settings.young_scale != 1) {
    throw InputError(fmt::format(
        "--young-scale: {:g} with contact.law = linear (accepted: 1; the linear law's stiffness "
        "is contact.stiffness)",
        settings.young_scale));
  }
}

// The step: the settings' (refused above the stable bound without unsafe_dt) or the bound's
// recommendation.
double chosen_dt(const TimeStepBound& bound, const RunSettings& settings) {
  if (settings.dt > 0) {
    if (settings.dt > bound.stable && !settings.unsafe_dt) {
      throw InputError(fmt::format(
          "--dt: {:g} s is above the stable bound {:g} s ({} step of the smallest particle; "
          "accepted: dt <= {:g} s, or add --unsafe-dt)",
          settings.dt, bound.stable, bound.limited_by, bound.stable));
    }
    return settings.dt;
  }
  if (!std::isfinite(bound.recommended)) {
    throw InputError("--dt: no effect bounds the time step (hertz, walls and drag are off; "
                     "accepted: give --dt explicitly)");
  }
  return bound.recommended;
}

// The scene's laws and constants in the force parameters, and the law's tabulation.
void set_up_laws(Context& c, const Scene& scene) {
  const Material& mat = scene.material;
  const ContactModuli moduli = contact_moduli(scene, c.settings.young_scale);
  c.params.pair.hertz = {moduli.pair, mat.damping};
  c.params.wall.hertz = {moduli.wall, mat.damping};
  c.params.pair.linear = {scene.stiffness, mat.damping};
  c.params.wall.linear = {scene.stiffness, mat.damping};
  c.tabulate = scene.law == ContactLaw::linear ? &detail::tabulate_contacts<detail::LinearLaw>
                                               : &detail::tabulate_contacts<detail::HertzLaw>;
  c.params.poisson = mat.poisson;
  c.params.wall_poisson = scene.wall.poisson;
  c.params.wall_young = moduli.wall_young;
  c.params.friction.coefficient = mat.friction;
  c.params.gravity.acceleration = scene.gravity;
  c.params.box = Box::from(c.bed.domain);
}

struct Totals {
  double r_max = 0;       // m, the largest radius
  double total_mass = 0;  // kg
};

// Velocities (zero when the bed has none), masses, drag coefficients, the integrator's arrays,
// the neighbour list's cells and the walls' constants, for all of the bed's particles.
Totals set_up_particles(Context& c, const Scene& scene) {
  bed::Bed& bed = c.bed;
  const std::size_t n = c.n;
  if (!bed.has_velocity()) {
    bed.vx.assign(n, 0.0);
    bed.vy.assign(n, 0.0);
    bed.vz.assign(n, 0.0);
  }
  c.mass.resize(n);
  c.inv_mass.resize(n);
  c.weight.resize(n);
  c.drag.resize(n);
  const bool stiffness = scene.fines.scaling == FinesScaling::stiffness;
  c.young.assign(stiffness ? n : 0, 0.0);
  const double young = contact_moduli(scene, c.settings.young_scale).young;
  for (auto* v : {&c.fx, &c.fy, &c.fz}) v->assign(n, 0.0);
  Totals totals;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = bed.radius[i];
    // docs/physics.md §4 "Fines": gravity and drag act on the particle as it is; only its
    // inertia (mass scaling) or its modulus (stiffness scaling) is scaled.
    c.weight[i] = bed::sphere_volume(r) * scene.material.density;
    c.mass[i] = c.weight[i] * fines_mass_factor(scene.fines, r);
    c.inv_mass[i] = 1.0 / c.mass[i];
    if (stiffness) c.young[i] = young * fines_stiffness_factor(scene.fines, r);
    c.drag[i] = stokes_drag_coefficient({scene.fluid_viscosity}, r);
    totals.r_max = std::max(totals.r_max, r);
    totals.total_mass += c.weight[i];
  }
  if (c.settings.integrator == Integrator::rk4) {
    for (auto* v : {&c.x0, &c.y0, &c.z0, &c.u0, &c.v0, &c.w0, &c.sx, &c.sy, &c.sz, &c.su, &c.sv,
                    &c.sw}) {
      v->assign(n, 0.0);
    }
  }
  const double skin = c.settings.skin > 0 ? c.settings.skin : 0.2 * totals.r_max;
  c.list.configure(c.params.box, totals.r_max, skin, n);
  if (scene.law == ContactLaw::linear) {
    detail::tabulate_wall_constants<detail::LinearLaw>(c.tables, c.arrays(), c.params);
  } else {
    detail::tabulate_wall_constants<detail::HertzLaw>(c.tables, c.arrays(), c.params);
  }
  return totals;
}

constexpr std::uint64_t kNotQuiet = ~std::uint64_t{0};

// What the phases of a run (settle, lid) share: the state, the step count, the snapshots and the
// rest test.
struct DropRun {
  DropRun(bed::Bed& b, const Scene& sc, const RunSettings& s) : scene(sc), settings(s), c(b, s) {}
  const Scene& scene;
  const RunSettings& settings;
  Context c;
  void (*step_once)(Context&, std::uint64_t) = nullptr;  // step_verlet or step_rk4
  std::optional<TrajectoryWriter> trajectory;
  std::uint64_t step = 0;
  bool stopped = false;    // by the observer: no later phase runs
  bool inserting = false;  // particles still enter (Insertion): rest is not tested
  double rest_energy = 0;  // J, RestCriteria::kinetic_energy or its default
  std::uint64_t rest_every = 1, window_steps = 0;
  std::uint64_t thermo_every = 0;  // RunSettings::thermo_every resolved
  std::uint64_t thermo_last = kNotQuiet;  // step of the last row
  RunSummary summary;

  double time() const { return static_cast<double>(step) * c.dt; }
  double time_at(std::uint64_t at) const { return static_cast<double>(at) * c.dt; }

  // Steps until `last_step`, rest (with until_rest) or the observer's stop; `before` runs before
  // each step, `after` after it (true ends the phase). Returns true when the phase ended at rest.
  // Progress reports the phase's end as `progress_end` (s).
  template <class Before, class After>
  bool advance(std::uint64_t last_step, bool until_rest, double progress_end, Before&& before,
               After&& after) {
    std::uint64_t quiet_since = kNotQuiet;  // first step of the current quiet stretch
    while (step < last_step) {
      before();
      step_once(c, step + 1);
      ++step;
      const double now = time();
      if (trajectory && step % settings.trajectory_every == 0) trajectory->write(step, now, c.bed);
      if (settings.observer && step % settings.observe_every == 0 &&
          settings.observer(step, now, c.bed)) {
        stopped = true;
        return false;
      }
      if (settings.thermo && step % thermo_every == 0) thermo();
      if (after()) return false;
      if (until_rest && !inserting && step % rest_every == 0 && quiet_for_window(quiet_since)) {
        return true;
      }
      if (settings.progress && step % settings.progress_every == 0) report(progress_end);
    }
    return false;
  }
  // The rest test (RestCriteria) at this step: true once the bed has been quiet for the window.
  bool quiet_for_window(std::uint64_t& quiet_since) const {
    double ke, vmax;
    kinetic_state(c, ke, vmax);
    if (ke < rest_energy && vmax < settings.rest.max_speed) {
      if (quiet_since == kNotQuiet) quiet_since = step;
      return step - quiet_since >= window_steps;
    }
    quiet_since = kNotQuiet;
    return false;
  }
  // A row of the thermo table: the state of the particles in the box (insertion: those in).
  void thermo() {
    ThermoRow row = thermo_row(c.bed, scene, c.n);
    row.step = step;
    row.time = time();
    double vmax;
    kinetic_state(c, row.kinetic_energy, vmax);
    settings.thermo(row);
    thermo_last = step;
  }
  void report(double progress_end) const {
    Progress p;
    p.step = step;
    p.time = time();
    p.t_end = progress_end;
    kinetic_state(c, p.kinetic_energy, p.max_speed);
    settings.progress(p);
  }
};

const auto never = [] { return false; };

// The drop solver's side of insertion (insertion.hpp): the bed is the pool and its first c.n
// particles are in, so the per-particle tables, made for the whole pool, stay indexed as they are.
class SolverInsertion {
 public:
  explicit SolverInsertion(DropRun& run) : run_(run), c_(run.c) {
    if (run.settings.insertion.enabled) c_.n = 0;
  }

  const RunSettings& settings() const { return run_.settings; }
  const Scene& scene() const { return run_.scene; }
  RunSummary& summary() { return run_.summary; }
  double time() const { return run_.time(); }
  const Box& box() const { return c_.params.box; }
  const bed::Bed& pool() const { return c_.bed; }
  std::size_t inserted() const { return c_.n; }
  const bed::Bed& bed() const { return c_.bed; }
  void place(std::size_t k, const double p[3], double vz) {
    bed::Bed& bed = c_.bed;
    bed.x[k] = p[0];
    bed.y[k] = p[1];
    bed.z[k] = p[2];
    bed.vx[k] = 0;
    bed.vy[k] = 0;
    bed.vz[k] = vz;
    ++c_.n;
  }
  void entered() {
    c_.rebuild();
    ++c_.rebuilds;
  }
  void set_inserting(bool on) { run_.inserting = on; }
  void end_insertion() {
    bed::Bed& bed = c_.bed;
    for (auto* v : {&bed.x, &bed.y, &bed.z, &bed.radius, &bed.vx, &bed.vy, &bed.vz}) v->resize(c_.n);
    bed.id.resize(c_.n);
    if (!bed.material.empty()) bed.material.resize(c_.n);
    if (!bed.temperature.empty()) bed.temperature.resize(c_.n);
    if (!bed.phase.empty()) bed.phase.resize(c_.n);
  }
  void set_rest_energy(double energy) { run_.rest_energy = energy; }

 private:
  DropRun& run_;
  Context& c_;
};

// The drop solver's side of the lid (lid_phase.hpp).
class SolverLid {
 public:
  SolverLid(DropRun& run, double (*force)(const Context&, bool))
      : run_(run), c_(run.c), force_(force), damping_(run.scene.has(kDamping)) {}

  const RunSettings& settings() const { return run_.settings; }
  RunSummary& summary() { return run_.summary; }
  bool stopped() const { return run_.stopped; }
  double time() const { return run_.time(); }
  double dt() const { return c_.dt; }
  const bed::Bed& bed() const { return c_.bed; }
  std::size_t count() const { return c_.n; }
  Box& box() { return c_.params.box; }
  void set_top_velocity(double v) { c_.params.top_velocity = v; }
  void keep_top(double z) { c_.bed.domain.upper[2] = z; }

  // A list build: the face tables list the particles within r + skin of the lid.
  void top_reset() {
    c_.rebuild();
    ++c_.rebuilds;
    lid_at_build_ = c_.params.box.upper[2];
    builds_ = c_.rebuilds;
  }
  // Particles move at most skin/2 between builds, so a rebuild whenever the lid has moved skin/2
  // keeps every particle that can touch it listed.
  void top_moved() {
    if (std::abs(lid_at_build_ - c_.params.box.upper[2]) > 0.5 * c_.list.skin()) {
      c_.rebuild();
      ++c_.rebuilds;
    }
  }
  double top_force() {
    if (c_.rebuilds != builds_) {  // in top_moved or in the step's own rebuild_if_needed
      builds_ = c_.rebuilds;
      lid_at_build_ = c_.params.box.upper[2];
    }
    return force_(c_, damping_);
  }
  template <class Before, class After>
  bool advance(std::uint64_t steps, bool until_rest, Before&& before, After&& after) {
    const std::uint64_t last = run_.step + steps;
    return run_.advance(last, until_rest, run_.time_at(last), before, after);
  }

 private:
  DropRun& run_;
  Context& c_;
  double (*force_)(const Context&, bool);  // lid_force<Law>
  bool damping_;
  double lid_at_build_ = 0;    // m, where the lid was at the last list build
  std::uint64_t builds_ = 0;   // c.rebuilds when lid_at_build_ was taken
};

// The summary of the end state: steps, energies, overlaps, lost particles.
void summarise(DropRun& run, const TimeStepBound& bound) {
  const Context& c = run.c;
  RunSummary& summary = run.summary;
  summary.n = c.n;
  summary.steps = run.step;
  summary.sim_time = run.time();
  summary.dt = c.dt;
  summary.dt_stable = bound.stable;
  summary.dt_limited_by = bound.limited_by;
  summary.dt_limiting_radius = bound.limiting_radius;
  kinetic_state(c, summary.kinetic_energy, summary.max_speed);
  const Overlap overlap = max_overlap(c.bed, run.scene);
  summary.max_overlap = overlap.relative;
  summary.max_overlap_m = overlap.absolute;
  summary.max_overlap_full_stiffness = full_stiffness_overlap(overlap, run.scene, run.settings.young_scale);
  summary.lost = count_outside(c.bed, c.n);
  summary.neighbour_rebuilds = c.rebuilds;
}

}  // namespace

void check_run_settings(const RunSettings& s) {
  const auto bad = [](const char* what, double v, const char* accepted) {
    throw InputError(fmt::format("{}: {:g} is out of range (accepted: {})", what, v, accepted));
  };
  if (!(s.t_end >= 0) || !std::isfinite(s.t_end)) bad("--t-end", s.t_end, "T >= 0 s");
  if (!s.until_rest && !(s.t_end > 0)) bad("--t-end", s.t_end, "T > 0 s, or --until-rest");
  if (!(s.dt >= 0) || !std::isfinite(s.dt)) bad("--dt", s.dt, "dt > 0 s");
  if (!(s.skin >= 0) || !std::isfinite(s.skin)) bad("skin", s.skin, ">= 0 m");
  if (!s.trajectory.empty() && s.trajectory_every == 0) {
    throw InputError("--every: 0 with --trajectory (accepted: K >= 1 steps)");
  }
  // Keys as deposit's options name them (rest.kinetic_energy has no option: library callers).
  if (!(s.rest.max_speed > 0) || !std::isfinite(s.rest.max_speed))
    bad("--rest.speed", s.rest.max_speed, "v > 0 m/s");
  if (!(s.rest.window >= 0) || !std::isfinite(s.rest.window))
    bad("--rest.window", s.rest.window, "window >= 0 s");
  if (!(s.rest.kinetic_energy >= 0)) bad("rest kinetic energy", s.rest.kinetic_energy, ">= 0 J");
}

RunSummary run_deposition(bed::Bed& bed, const Scene& scene, const RunSettings& settings) {
  check_run(bed, scene, settings);
  return detail::run_drop_on_engine(bed, scene, settings);
}

RunSummary detail::run_on_drop_solver(bed::Bed& bed, const Scene& scene, const RunSettings& settings) {
  check_run(bed, scene, settings);
  if (detail::needs_rotation(scene)) {
    throw InputError("the drop solver: friction.model = history or material.rolling > 0 (accepted: "
                     "laws without particle rotation)");
  }
  const auto started = std::chrono::steady_clock::now();
  const detail::FlushSubnormals flush;  // a settled bed's speeds decay into subnormals
  const TimeStepBound bound = time_step_bound(bed, scene, settings.young_scale);
  DropRun run(bed, scene, settings);
  Context& c = run.c;
  c.n = bed.n();
  c.threads = bed.n() < settings.parallel_min_particles ? 1
              : settings.threads > 0 ? settings.threads
                                     : omp_get_max_threads();
  c.dt = chosen_dt(bound, settings);
  set_up_laws(c, scene);
  const Totals totals = set_up_particles(c, scene);
  SolverInsertion inserting(run);
  detail::Insertion<SolverInsertion> insertion(inserting, totals.r_max);
  c.rebuild();

  const bool linear = scene.law == ContactLaw::linear;
  constexpr auto masks = std::make_index_sequence<kAllEffects + 1>{};
  c.forces = linear ? force_loop<detail::LinearLaw>(scene.effects & kAllEffects, masks)
                    : force_loop<detail::HertzLaw>(scene.effects & kAllEffects, masks);
  run.step_once = settings.integrator == Integrator::rk4 ? &step_rk4 : &step_verlet;
  c.compute_forces();  // Verlet needs F(t0)

  const double t_end = settings.t_end > 0 ? settings.t_end : 1.0;
  const auto total_steps = static_cast<std::uint64_t>(std::ceil(t_end / c.dt - 1e-9));
  const RestCriteria& rest = settings.rest;
  run.rest_energy = rest.kinetic_energy > 0
                        ? rest.kinetic_energy
                        : 1e-2 * 0.5 * totals.total_mass * rest.max_speed * rest.max_speed;
  // Rest checks: about ten per window (at most every 100 steps), never every step.
  run.rest_every = static_cast<std::uint64_t>(
      std::clamp(std::floor(rest.window / c.dt / 10.0), 1.0, 100.0));
  run.window_steps = static_cast<std::uint64_t>(std::ceil(rest.window / c.dt));
  if (!settings.trajectory.empty()) {
    run.trajectory.emplace(settings.trajectory, bed);
    run.trajectory->write(0, 0.0, bed);
  }
  run.thermo_every = settings.thermo_every > 0 ? settings.thermo_every : thermo_interval(total_steps);
  if (settings.thermo) run.thermo();

  run.summary.at_rest = run.advance(total_steps, settings.until_rest, t_end,
                                    [&] { insertion.insert_due(); }, never);
  if (run.inserting) insertion.end("time", run.time());
  if (settings.lid.enabled && !run.stopped) {
    SolverLid lid(run, linear ? &lid_force<detail::LinearLaw> : &lid_force<detail::HertzLaw>);
    detail::LidPhase<SolverLid>(lid).run();
  }
  if (run.trajectory) {
    if (run.step % settings.trajectory_every != 0) run.trajectory->write(run.step, run.time(), bed);
    run.trajectory->close();
  }
  if (settings.thermo && run.thermo_last != run.step) run.thermo();
  summarise(run, bound);
  if (settings.progress) run.report(run.summary.sim_time);
  RunSummary& summary = run.summary;
  summary.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const double particle_steps = static_cast<double>(c.n) * static_cast<double>(run.step);
  summary.particle_steps_per_s = summary.wall_time > 0 ? particle_steps / summary.wall_time : 0;
  return summary;
}

}  // namespace powderbed::dem
