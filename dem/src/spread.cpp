// The spreading run of spread.hpp: velocity Verlet on positions and rotations, contact history
// per neighbour pair (kept across neighbour-list builds) and per particle and wall, the tool's
// prescribed motion, the supply and the layers (docs/deposit-spread.md).
#include "powderbed/dem/spread.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "box.hpp"
#include "contact_model.hpp"
#include "dosing_platform.hpp"
#include "engine.hpp"
#include "flush_subnormals.hpp"
#include "parallel.hpp"
#include "sleep.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/bed/surface_contacts.hpp"
#include "powderbed/dem/contact_moduli.hpp"
#include "powderbed/dem/time_step.hpp"

namespace powderbed::dem {

ToolShape parse_tool_shape(const std::string& text, const std::string& option) {
  return bed::parse_word(text, option, kToolShapeWords, "a recoater tool");
}

namespace {

using detail::Box;
using detail::Engine;
using detail::ActiveContacts;
using detail::kWallValues;
using detail::largest_radius;
using detail::kContactHistory;
using detail::kPruneMargin;
using detail::default_skin;
using detail::kTool;

void check_tool(const Recoater& t, const Box& box) {
  const auto require = require_in_range;  // bed/errors.hpp
  const auto finite = [](double v) { return std::isfinite(v); };
  require(finite(t.gap) && t.gap > 0, "recoater.gap", t.gap, "gap > 0 m above the plate");
  require(finite(t.speed) && t.speed > 0, "recoater.speed", t.speed, "speed > 0 m/s");
  require(finite(t.delay) && t.delay >= 0, "recoater.delay", t.delay, "delay >= 0 s");
  require(finite(t.settle) && t.settle >= 0, "recoater.settle", t.settle, "settle >= 0 s");
  require(finite(t.omega), "recoater.omega", t.omega, "a finite rad/s");
  if (t.shape == ToolShape::blade) {
    require(finite(t.thickness) && t.thickness > 0, "recoater.thickness", t.thickness,
            "thickness > 0 m");
    require(finite(t.edge_radius) && t.edge_radius >= 0 && 2 * t.edge_radius <= t.thickness,
            "recoater.edge-radius", t.edge_radius, "0 <= edge radius <= thickness / 2");
  } else {
    require(finite(t.radius) && t.radius > 0, "recoater.radius", t.radius, "radius > 0 m");
  }
  require(finite(t.start) && t.start >= box.lower[0] && t.start <= box.upper[0], "recoater.start",
          t.start, "a start inside the box along x");
  if (!(finite(t.end) && t.end > t.start && t.end <= box.upper[0])) {
    throw InputError(fmt::format(
        "recoater.end: {:g} (accepted: recoater.start {:g} < end <= the box's end {:g} m; the "
        "tool moves along +x)",
        t.end, t.start, box.upper[0]));
  }
  if (!(t.gap < box.length[2])) {
    throw InputError(
        fmt::format("recoater.gap: {:g} m is not below the box's top (accepted: gap < {:g} m)",
                    t.gap, box.length[2]));
  }
}

// The layer's supply through the public add_layer_supply (spread.hpp), with the run's floor.
std::size_t add_supply(Engine& run, std::uint64_t layer) {
  return add_layer_supply(run.bed, run.settings, run.floor, layer);
}

void check_tool_clear(const Engine& run) {
  for (std::size_t i = 0; i < run.n(); ++i) {
    ToolContact t;
    if (!tool_contact(run.profile, run.bed.x[i] - run.tool_x, run.bed.z[i], run.bed.radius[i], t))
      continue;
    throw InputError(fmt::format(
        "recoater.start: the tool at x = {:g} m overlaps particle id {} at ({:g}, {:g}) "
        "(accepted: a tool that starts clear of the powder, behind it)",
        run.tool_x, run.bed.id[i], run.bed.x[i], run.bed.z[i]));
  }
}

ActiveContacts from_state(const SpreadState& s, const bed::Bed& bed) {
  std::unordered_map<std::uint64_t, std::uint32_t> index;
  for (std::size_t i = 0; i < bed.n(); ++i) index[bed.id[i]] = static_cast<std::uint32_t>(i);
  ActiveContacts a;
  const std::size_t count = s.pair_ids.size() / 2;
  for (std::size_t c = 0; c < count; ++c) {
    a.i.push_back(index.at(s.pair_ids[2 * c]));
    a.j.push_back(index.at(s.pair_ids[2 * c + 1]));
  }
  a.h = s.pair_history;
  return a;
}

SpreadState to_state(const Engine& run, const ActiveContacts& a) {
  SpreadState s;
  s.dt = run.dt;
  s.tool_x = run.tool_x;
  s.wx = run.wx;
  s.wy = run.wy;
  s.wz = run.wz;
  for (std::size_t c = 0; c < a.i.size(); ++c) {
    s.pair_ids.push_back(run.bed.id[a.i[c]]);
    s.pair_ids.push_back(run.bed.id[a.j[c]]);
  }
  s.pair_history = a.h;
  s.wall_history = run.wall_history;
  return s;
}

// Removes the powder the tool pushed past its end — centres in front of its front face where it
// stopped, the machine's overflow slot — from the bed and the state; returns how many. With
// `chamber` only the centres above `level` (the tool's bottom, the chamber's edge) go: the
// powder under it stays, so the bed reaches the box's far wall (SpreadSettings::chamber).
std::size_t remove_overflow(bed::Bed& bed, SpreadState& s, double front, bool chamber, double level) {
  std::vector<char> keep(bed.n());
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const bool under_the_edge = chamber && bed.z[i] < level;
    keep[i] = bed.x[i] <= front || under_the_edge ? 1 : 0;
  }
  return remove_particles(bed, s, keep);
}

}  // namespace

std::size_t add_layer_supply(bed::Bed& bed, const SpreadSettings& s, const bed::HeightMap& floor,
                             std::uint64_t layer) {
  if (!s.supply) return 0;  // the powder is already in the bed
  const bed::Domain& box = bed.domain;
  const double front = s.tool.start + tool_half_extent(tool_profile(s.tool, box.lower[2] + s.tool.gap));
  if (!(s.supply_x0 >= front && s.supply_x1 > s.supply_x0 && s.supply_x1 <= box.upper[0])) {
    throw InputError(fmt::format(
        "supply.x0, supply.x1: {:g}, {:g} (accepted: the tool's front {:g} <= x0 < x1 <= the "
        "box's end {:g} m: the supply lies in front of the tool)",
        s.supply_x0, s.supply_x1, front, box.upper[0]));
  }
  double base = floor.empty() ? box.lower[2] : std::max(box.lower[2], floor.highest());
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double r = bed.radius[i];
    if (bed.x[i] + r > s.supply_x0 && bed.x[i] - r < s.supply_x1) base = std::max(base, bed.z[i] + r);
  }
  bed::Domain region = bed.domain;
  region.lower[0] = s.supply_x0;
  region.upper[0] = s.supply_x1;
  region.lower[2] = base;
  region.upper[2] = base + s.supply_height;
  if (!(s.supply_height > 0) || region.upper[2] > box.upper[2]) {
    throw InputError(fmt::format(
        "supply.height: {:g} m on the powder at z = {:g} m does not fit the box (accepted: 0 < "
        "height <= {:g} m)",
        s.supply_height, base, box.upper[2] - base));
  }
  region.periodic = {false, false, false};
  const bed::Bed more = s.supply(region, layer);
  std::uint64_t next = 0;
  for (const std::uint64_t id : bed.id) next = std::max(next, id + 1);
  for (std::size_t k = 0; k < more.n(); ++k) {
    bed.x.push_back(more.x[k]);
    bed.y.push_back(more.y[k]);
    bed.z.push_back(more.z[k]);
    bed.radius.push_back(more.radius[k]);
    bed.id.push_back(next++);
    bed.vx.push_back(0);
    bed.vy.push_back(0);
    bed.vz.push_back(0);
    if (!bed.material.empty()) bed.material.push_back(0);
    if (!bed.temperature.empty()) bed.temperature.push_back(bed.temperature.front());
    if (!bed.phase.empty()) bed.phase.push_back(0);
  }
  return more.n();
}

std::size_t remove_particles(bed::Bed& bed, SpreadState& s, const std::vector<char>& keep) {
  std::unordered_set<std::uint64_t> gone;
  for (std::size_t i = 0; i < bed.n(); ++i)
    if (!keep[i]) gone.insert(bed.id[i]);
  const auto compact = [&](auto& values, std::size_t stride) {
    if (values.empty()) return;
    std::size_t k = 0;
    for (std::size_t i = 0; i < keep.size(); ++i) {
      if (!keep[i]) continue;
      std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(i * stride), stride,
                  values.begin() + static_cast<std::ptrdiff_t>(k * stride));
      ++k;
    }
    values.resize(k * stride);
  };
  for (auto* v : {&bed.x, &bed.y, &bed.z, &bed.radius, &bed.vx, &bed.vy, &bed.vz, &bed.temperature,
                  &s.wx, &s.wy, &s.wz}) {
    compact(*v, 1);
  }
  compact(bed.id, 1);
  compact(bed.material, 1);
  compact(bed.phase, 1);
  compact(s.wall_history, kWallValues);
  std::vector<std::uint64_t> ids;
  std::vector<double> history;
  for (std::size_t c = 0; c < s.pair_ids.size() / 2; ++c) {
    if (gone.count(s.pair_ids[2 * c]) || gone.count(s.pair_ids[2 * c + 1])) continue;
    ids.insert(ids.end(), s.pair_ids.begin() + static_cast<std::ptrdiff_t>(2 * c),
               s.pair_ids.begin() + static_cast<std::ptrdiff_t>(2 * c + 2));
    history.insert(history.end(), s.pair_history.begin() + static_cast<std::ptrdiff_t>(kContactHistory * c),
                   s.pair_history.begin() + static_cast<std::ptrdiff_t>(kContactHistory * (c + 1)));
  }
  s.pair_ids = std::move(ids);
  s.pair_history = std::move(history);
  return gone.size();
}

namespace {

double largest_overlap(const Engine& run) {
  double worst = 0;
  const std::uint32_t* owner = run.list.owners();
  const std::uint32_t* partner = run.list.partners();
  for (std::size_t k = 0; k < run.touching.size(); ++k) {
    const std::uint32_t i = owner[k], j = partner[k];
    const double ex = run.box.image(0, run.bed.x[j] - run.bed.x[i]);
    const double ey = run.box.image(1, run.bed.y[j] - run.bed.y[i]);
    const double ez = run.box.image(2, run.bed.z[j] - run.bed.z[i]);
    const double delta = run.pair_reach[k] - std::sqrt(ex * ex + ey * ey + ez * ez);
    if (delta > 0) worst = std::max(worst, delta / std::min(run.bed.radius[i], run.bed.radius[j]));
  }
  return worst;
}

void finish_layer(const Engine& run, LayerSummary& out, double window_x0, double window_x1,
                  double bottom) {
  const bed::Bed& bed = run.bed;
  const Box& box = run.box;
  double solid = 0;
  for (std::size_t i = 0; i < run.n(); ++i) {
    const double r = bed.radius[i];
    out.kinetic_energy += 0.5 * run.weight[i] *
                          (bed.vx[i] * bed.vx[i] + bed.vy[i] * bed.vy[i] + bed.vz[i] * bed.vz[i]);
    out.max_speed = std::max(out.max_speed, std::sqrt(bed.vx[i] * bed.vx[i] +
                                                      bed.vy[i] * bed.vy[i] + bed.vz[i] * bed.vz[i]));
    bool outside = bed.z[i] < box.lower[2];
    for (int a = 0; a < 2; ++a) {
      const double p = a == 0 ? bed.x[i] : bed.y[i];
      outside = outside || (!box.periodic[a] && (p < box.lower[a] || p > box.upper[a]));
    }
    out.lost += outside ? 1 : 0;
    if (bed.x[i] >= window_x0 && bed.x[i] < window_x1 && bed.z[i] < bottom) {
      solid += bed::sphere_volume(r);
    }
  }
  const double volume = (window_x1 - window_x0) * box.length[1] * (bottom - box.lower[2]);
  out.density_under_gap = volume > 0 ? solid / volume : 0.0;
  out.n = run.n();
}

// A floor the run can stand on: a grid of at least 2 x 2 nodes with one height each, inside
// the box.
void check_floor(const bed::HeightMap& floor, const Box& box) {
  if (floor.empty()) return;
  if (floor.nx < 2 || floor.ny < 2 || floor.z.size() != floor.nx * floor.ny || !(floor.dx > 0) ||
      !(floor.dy > 0)) {
    throw InputError(fmt::format(
        "floor: a height map of {} heights on {} x {} nodes (accepted: nx, ny >= 2, one height "
        "per node, spacings > 0)",
        floor.z.size(), floor.nx, floor.ny));
  }
  for (const double h : floor.z) {
    if (!(h >= box.lower[2] && h < box.upper[2])) {
      throw InputError(fmt::format(
          "floor: a height {:g} m outside the box (accepted: the plate {:g} <= h < the box's top "
          "{:g} m)",
          h, box.lower[2], box.upper[2]));
    }
  }
}

// Along a periodic axis of the box the floor is periodic too (bed::HeightMap::periodic_x): its
// grid must span the box there, and its two edge rows become one (their mean, as fusion leaves
// them). Held flat beyond the seam instead, the surface under a sphere changed the moment it
// crossed, and the jump in overlap threw powder off at up to 1.5 m/s: a build's later layers
// never came to rest (docs/build.md "Limits").
void make_floor_periodic(bed::HeightMap& floor, const Box& box) {
  if (floor.empty()) return;
  for (int axis = 0; axis < 2; ++axis) {
    if (box.periodic[axis] && !floor.spans(axis, box.lower[axis], box.length[axis])) {
      throw InputError(fmt::format(
          "floor: the box is periodic along {} but the floor's grid does not span it (accepted: "
          "nodes from the box's lower face {:g} m to its upper face {:g} m along a periodic axis)",
          axis == 0 ? "x" : "y", box.lower[axis], box.upper[axis]));
    }
  }
  floor.periodic_x = box.periodic[0];
  floor.periodic_y = box.periodic[1];
  floor.join_periodic_edges();
}

// A continued bed's particles lie on the solid under them, not in it: a centre below the
// floor's height at its (x, y) would be pushed out at once with the solid's whole stiffness.
void check_above_floor(const bed::Bed& bed, const bed::HeightMap& floor) {
  if (floor.empty()) return;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double h = floor.at(bed.x[i], bed.y[i]);
    if (bed.z[i] < h) {
      throw InputError(fmt::format(
          "--in: particle {} (id {}) has its centre at z = {:g} m, inside the solid whose top is "
          "at {:g} m there (accepted: a bed written by a spreading run, unchanged)",
          i, bed.id[i], bed.z[i], h));
    }
  }
}

// SpreadSettings::sleep: positive speeds, the wake speed above the sleep speed (else a calm
// rim wakes what it touches); not beside freezing, whose frozen particles never wake.
void check_sleep(const SpreadSettings& settings) {
  const SleepSettings& s = settings.sleep;
  if (!s.on) return;
  require_in_range(std::isfinite(s.speed) && s.speed > 0, "sleep.speed", s.speed, "speed > 0 m/s");
  require_in_range(std::isfinite(s.wake_speed) && s.wake_speed > s.speed, "sleep.wake-speed", s.wake_speed,
                   "a speed above sleep.speed");
  if (s.steps < 1) throw InputError("sleep.steps: 0 (accepted: steps >= 1)");
  if (settings.freeze_depth > 0) {
    throw InputError(fmt::format("recoater.freeze-depth: {:g} m with sleep.on = true (accepted: one of the two; "
                                 "frozen powder never wakes)",
                                 settings.freeze_depth));
  }
}

// SpreadSettings::platform_edge: under the supply and short of where the tool stops (it must
// carry the powder off the platform), with a tool.
void check_platform(const SpreadSettings& s) {
  if (!s.platform_edge) return;
  const double edge = *s.platform_edge, low = s.supply ? s.supply_x1 : s.tool.start;
  if (!s.with_tool || !std::isfinite(edge) || edge < low || edge >= s.tool.end) {
    throw InputError(fmt::format(
        "supply.platform-edge: {:g} m (accepted: with a recoater, {} {:g} <= edge < recoater.end "
        "{:g} m: the supply lies on the platform and the tool carries it off)",
        edge, s.supply ? "supply.x1" : "recoater.start", low, s.tool.end));
  }
}

void check_settings(const bed::Bed& bed, const Scene& scene, const SpreadSettings& settings,
                    const Box& box) {
  if (bed.domain.dimension != 3 || bed.domain.periodic[2]) {
    throw InputError("recoater: the box must be 3D with z not periodic (accepted: periodic x, y)");
  }
  if (settings.with_tool) check_tool(settings.tool, box);
  if (!scene.has(kWalls) && (settings.with_tool || !settings.floor.empty())) {
    throw InputError("effects.walls: off in a spreading run (accepted: on; the plate, the floor and "
                     "the tool are walls)");
  }
  if (!settings.rotation && (scene.friction_model == FrictionModel::history || scene.material.rolling > 0)) {
    throw InputError(std::string(scene.material.rolling > 0 ? "material.rolling" : "friction.model = history") +
                     ": needs particles that turn (accepted: friction.model = sliding and "
                     "material.rolling = 0 when the particles do not rotate)");
  }
  if (!(settings.layers >= 1)) throw InputError("--layers: 0 (accepted: N >= 1)");
  require_in_range(std::isfinite(settings.layer_thickness) && settings.layer_thickness >= 0,
                   "recoater.layer-thickness", settings.layer_thickness, "thickness >= 0 m");
  require_in_range(std::isfinite(settings.freeze_depth) && settings.freeze_depth >= 0,
                   "recoater.freeze-depth", settings.freeze_depth, "depth >= 0 m; 0: off");
  check_sleep(settings);
  check_floor(settings.floor, box);
  check_platform(settings);
  if (!settings.until_rest) return;
  const RestCriteria& rest = settings.rest;
  require_in_range(std::isfinite(rest.max_speed) && rest.max_speed > 0, "rest.speed",
                   rest.max_speed, "v > 0 m/s");
  require_in_range(std::isfinite(rest.window) && rest.window >= 0, "rest.window", rest.window,
                   "window >= 0 s");
  require_in_range(std::isfinite(settings.rest_cap) && settings.rest_cap > 0,
                   "recoater.rest-cap", settings.rest_cap, "cap > 0 s");
}

// One call of run_spread: the run, its summary, the state a layer's end leaves and the
// contacts it carries into the next list build.
struct Spreader {
  Spreader(bed::Bed& b, const Scene& sc, const SpreadSettings& st, const SpreadState* r)
      : bed(b), scene(sc), settings(st), restart(r), run(b, sc, st) {}
  bed::Bed& bed;
  const Scene& scene;
  const SpreadSettings& settings;
  const SpreadState* restart;
  Engine run;
  detail::SleepBook sleep_book{run};
  SpreadSummary summary;
  SpreadState state;
  ActiveContacts carried;
  // The solid the powder lies on (SpreadSettings::floor or the restart's; empty: the flat
  // plate): run.floor is this with the dosing platform raised, and the state keeps this.
  bed::HeightMap solid_floor;
  std::uint64_t step = 0;
  double particle_steps = 0;  // the particles each step moved (a layer's overflow included)
  std::uint64_t thermo_every = 0;         // SpreadSettings::thermo_every resolved
  std::uint64_t thermo_last = ~std::uint64_t{0};  // step of the last thermo row

  // The interval of the thermo table, once the run's step count is known.
  void resolve_thermo(std::uint64_t run_steps) {
    if (thermo_every == 0)
      thermo_every = settings.thermo_every > 0 ? settings.thermo_every : thermo_interval(run_steps);
  }
  // A row of the thermo table at this step (the tool's layer and x with a tool).
  void thermo() {
    ThermoRow row = thermo_row(bed, scene, bed.n());
    row.step = step;
    row.time = static_cast<double>(step) * run.dt;
    row.kinetic_energy = run.kinetic_energy();
    if (settings.with_tool) {
      row.layer = state.layers_done + 1;
      row.tool_x = run.tool_x;
    }
    settings.thermo(row);
    thermo_last = step;
  }

  // The contact model, the (softened) moduli, gravity, and the restart's state.
  void set_up() {
    run.set_up();
    solid_floor = settings.floor.empty() && restart ? restart->floor : settings.floor;
    check_floor(solid_floor, run.box);
    make_floor_periodic(solid_floor, run.box);
    run.floor = solid_floor;
    if (!restart) return;
    if (restart->wx.size() != bed.n() ||
        restart->wall_history.size() != bed.n() * kWallValues) {
      throw InputError("--in: the bed's /restart group does not match its particles (accepted: "
                       "a bed written by a spreading run, unchanged)");
    }
    check_above_floor(bed, run.floor);
    state = *restart;
    step = state.step;
    run.wx = restart->wx;
    run.wy = restart->wy;
    run.wz = restart->wz;
    run.set_wall_history(restart->wall_history);
    carried = from_state(*restart, bed);
  }

  // The restart's step, or the engine's choice (Engine::set_time_step).
  void set_time_step() {
    const TimeStepBound bound = time_step_bound(bed, scene, settings.young_scale);
    summary.dt_stable = bound.stable;
    summary.dt_limited_by = bound.limited_by;
    summary.dt_limiting_radius = bound.limiting_radius;
    if (!restart) {
      run.set_time_step(bound);
      return;
    }
    if (restart->dt > bound.stable && !settings.unsafe_dt) {
      throw InputError(fmt::format(
          "--in: the bed's /restart time step {:g} s is above the stable bound {:g} s of this "
          "scene (accepted: a bed written by a spreading run of this scene, or add --unsafe-dt)",
          restart->dt, bound.stable));
    }
    run.dt = restart->dt;
    run.model.coefficients.dt = run.dt;
  }

  void rebuild() { run.rebuild(carried); }

  // `steps` steps, `before(s)` ahead of the s-th, or fewer when the observer stops the run (false);
  // the velocities are the last whole step's after. Progress is the share done of `planned`
  // steps of which `done` are behind (0: of `steps`; a layer plans its pass and its rest cap).
  template <class Before>
  bool advance(std::uint64_t steps, Before&& before, std::uint64_t planned = 0,
               std::uint64_t done = 0) {
    if (planned == 0) planned = steps;
    for (std::uint64_t s = 1; s <= steps; ++s) {
      before(s);
      run.step(step + 1);
      if (settings.sleep.on) sleep_book.after_step();
      ++step;
      if (settings.tool_force && settings.tool_force_every > 0 && step % settings.tool_force_every == 0) {
        ToolForceSample sample;
        sample.layer = state.layers_done + 1;
        sample.time = static_cast<double>(step) * run.dt;
        sample.x = run.tool_x;
        std::copy_n(run.tool_force, 3, sample.force);
        settings.tool_force(sample);
      }
      if (settings.progress && step % settings.progress_every == 0) {
        settings.progress(static_cast<double>(done + s) / static_cast<double>(planned),
                          run.kinetic_energy());
      }
      if (settings.thermo && step % thermo_every == 0) thermo();
      if (settings.frame && settings.frame_every > 0 && step % settings.frame_every == 0 &&
          settings.frame(step, static_cast<double>(step) * run.dt, run.whole_step_bed())) {
        run.sync(step);
        return false;
      }
      if (settings.observer) {  // it reads whole-step velocities: no kick stays pending
        run.sync(step);
        if (settings.observer(step, static_cast<double>(step) * run.dt, bed, run.wy)) return false;
      }
    }
    run.sync(step);
    if (settings.thermo && thermo_last != step) thermo();
    return true;
  }

  // The state of the run's end for a restart (layers_done is the caller's).
  void save_state(std::uint64_t layers_done) {
    carried = run.active();
    state = to_state(run, carried);
    state.floor = solid_floor;
    state.layers_done = layers_done;
    state.step = step;
    state.time = static_cast<double>(step) * run.dt;
  }

  // Without a tool: settings.t_end of the granular loop.
  void granular() {
    if (bed.n() == 0) throw InputError("deposit: the bed has no particles (accepted: N >= 1)");
    run.bound_floor();
    set_time_step();
    rebuild();
    run.forces();
    const auto steps = static_cast<std::uint64_t>(std::ceil(settings.t_end / run.dt - 1e-9));
    resolve_thermo(steps);
    if (settings.thermo) thermo();  // the state at the start, as a drop's table begins
    const std::uint64_t first = step;
    const bool stopped = settings.frame && settings.frame(step, static_cast<double>(step) * run.dt, bed);
    if (!stopped) advance(steps, [](std::uint64_t) {});
    particle_steps = static_cast<double>(bed.n()) * static_cast<double>(step - first);
    save_state(state.layers_done);
  }

  // The fastest speed of the powder whose centres lie short of x (behind the tool's back).
  double fastest_behind(double x) const {
    const bed::Bed& b = run.bed;
    double v2 = 0;
    for (std::size_t i = 0; i < run.n(); ++i) {
      if (b.x[i] < x) v2 = std::max(v2, b.vx[i] * b.vx[i] + b.vy[i] * b.vy[i] + b.vz[i] * b.vz[i]);
    }
    return std::sqrt(v2);
  }

  // Steps of settling to rest at most (SpreadSettings::rest_cap); 0 without until_rest.
  std::uint64_t rest_cap_steps() const {
    return settings.until_rest ? static_cast<std::uint64_t>(std::ceil(settings.rest_cap / run.dt)) : 0;
  }

  // SpreadSettings::until_rest: the tool stays where it stopped and the layer settles on until
  // the powder behind the tool's back has been slower than rest.max_speed for the window
  // (RestWatch; out.at_rest) or rest_cap has passed; progress counts on from the pass's `pass`
  // steps. False when the observer stopped the run.
  bool settle_to_rest(LayerSummary& out, double back, std::uint64_t pass) {
    RestWatch watch(settings.rest, run.dt);
    const std::uint64_t cap = rest_cap_steps();
    const auto calm = [&] { return fastest_behind(back) < settings.rest.max_speed; };
    bool rested = watch.check(0, calm());
    for (std::uint64_t done = 0; !rested && done < cap; done += watch.every()) {
      if (!advance(watch.every(), [](std::uint64_t) {}, pass + cap, pass + done)) return false;
      out.settle_time += static_cast<double>(watch.every()) * run.dt;
      rested = watch.check(done + watch.every(), calm());
    }
    out.at_rest = rested;
    return true;
  }

  // The per-particle arrays anew from `s` (the bed's particles after a removal), as a
  // continued run makes them.
  void reload(const SpreadState& s) {
    for (auto* v : {&run.mass, &run.wx, &run.wy, &run.wz}) v->clear();  // grow() redoes them
    run.wall.clear();
    run.grow();
    run.wx = s.wx;
    run.wy = s.wy;
    run.wz = s.wz;
    run.set_wall_history(s.wall_history);
    carried = from_state(s, bed);
  }

  // The overflow out of the bed and the state, and the per-particle arrays anew from the state.
  void drop_overflow(LayerSummary& out, double front) {
    out.overflow = remove_overflow(bed, state, front, settings.chamber, out.tool_bottom);
    out.n = bed.n();
    reload(state);
    if (bed.n() > 0) rebuild();  // an empty bed has no cells to size (the next supply rebuilds)
  }

  // SpreadSettings::platform_edge: the floor with the platform at `top` (the tool's bottom), and
  // out of the run the particles it reaches, those it overlaps deeper than the solid alone does
  // (1e-9 r: the flat plate's overlap and its triangles' round differently). Against the solid,
  // not the platform of the layer before, so that a continued run removes the same.
  void raise_platform(LayerSummary& out, double top) {
    bed::HeightMap raised =
        detail::with_platform(solid_floor, run.box, *settings.platform_edge, top, settings.tool.gap);
    make_floor_periodic(raised, run.box);
    const auto overlap = [&](const bed::HeightMap& f, std::size_t i) {
      const double r = bed.radius[i];
      if (f.empty()) return std::max(0.0, run.box.lower[2] + r - bed.z[i]);
      return bed::surface_overlap(f, bed.x[i], bed.y[i], bed.z[i], r);
    };
    std::vector<char> keep(bed.n(), 1);
    bool any = false;
    for (std::size_t i = 0; i < bed.n(); ++i) {
      keep[i] = overlap(raised, i) <= overlap(solid_floor, i) + 1e-9 * bed.radius[i] ? 1 : 0;
      any = any || !keep[i];
    }
    run.floor = raised;
    run.floor_reach = -1;  // bound_floor makes the bounds of the new floor
    if (!any) return;
    SpreadState now = to_state(run, carried);
    out.under_platform = remove_particles(bed, now, keep);
    reload(now);
  }

  // One layer: the tool back at its start and raised by the plate's descent, a new supply,
  // the pass, the settling, the state; false when the observer stopped it.
  bool layer() {
    const auto layer_started = std::chrono::steady_clock::now();
    const std::uint64_t number = state.layers_done + 1, first_step = step;
    const Recoater& tool = settings.tool;
    LayerSummary out;
    out.layer = number;
    const double asleep_before = sleep_book.asleep_steps;
    const std::uint64_t changes_before = sleep_book.changes;
    // The plate goes down by a layer thickness before each layer after the first; the bed
    // keeps the plate's frame, so the tool (and the supply above the powder) rise instead.
    const double plate_offset = static_cast<double>(number - 1) * settings.layer_thickness;
    const double bottom = run.box.lower[2] + tool.gap + plate_offset;
    if (!(bottom < run.box.upper[2])) {
      throw InputError("--layers: the tool rises above the box's top at layer " +
                       std::to_string(number) + " (accepted: a taller box or fewer layers)");
    }
    run.profile = tool_profile(tool, bottom);
    run.tool_x = tool.start;
    run.tool_v = 0;
    out.tool_bottom = bottom;
    if (settings.platform_edge) raise_platform(out, bottom);
    out.supplied = add_supply(run, number);
    run.grow();
    run.sort_by_cell(carried, run.freeze_below(bottom - settings.freeze_depth));
    out.frozen = run.n() - run.moving;
    run.find_frozen_in_reach();
    run.bound_floor();
    check_tool_clear(run);
    if (run.dt == 0) set_time_step();
    rebuild();
    run.forces();
    const auto delay = static_cast<std::uint64_t>(std::ceil(tool.delay / run.dt - 1e-9));
    const auto moving =
        static_cast<std::uint64_t>(std::ceil((tool.end - tool.start) / (tool.speed * run.dt) - 1e-9));
    const auto settle = static_cast<std::uint64_t>(std::ceil(tool.settle / run.dt - 1e-9));
    resolve_thermo((delay + moving + settle) * settings.layers);
    double force_x = 0, force_max = 0;
    const std::uint64_t pass = delay + moving + settle;
    bool finished = advance(pass, [&](std::uint64_t s) {
      const double travelled =
          static_cast<double>(std::min(moving, s > delay ? s - delay : 0)) * tool.speed * run.dt;
      run.tool_x = std::min(tool.end, tool.start + travelled);
      run.tool_v = s > delay && s <= delay + moving ? tool.speed : 0.0;
      if (s > 1) {  // the force of the step before, at the position it had
        const double* f = run.tool_force;
        force_max = std::max(force_max, std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]));
        if (s - 1 > delay && s - 1 <= delay + moving) force_x += f[0];
      }
    }, pass + rest_cap_steps());
    const double back = tool.end - tool_half_extent(run.profile);
    out.settle_time = tool.settle;
    if (finished && settings.until_rest) finished = settle_to_rest(out, back, pass);
    out.steps = step - first_step;
    particle_steps += static_cast<double>(run.n()) * static_cast<double>(out.steps);
    out.sim_time = static_cast<double>(step) * run.dt;
    out.max_tool_force = force_max;
    out.frozen_tool_contacts = run.frozen_tool_contacts;
    out.asleep = out.steps > 0 ? (sleep_book.asleep_steps - asleep_before) / static_cast<double>(out.steps) : 0.0;
    out.sleep_changes = sleep_book.changes - changes_before;
    out.mean_tool_force_x = moving > 0 ? force_x / static_cast<double>(moving) : 0.0;
    const double front = tool.end + tool_half_extent(run.profile);
    // The quick look's window starts where the layer does: at the supply's back, or past the
    // dosing platform (under it there is no powder to measure).
    finish_layer(run, out, std::max(settings.supply_x1, settings.platform_edge.value_or(settings.supply_x1)),
                 back, bottom);
    out.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - layer_started).count();
    save_state(number);
    state.plate_offset = plate_offset;
    if (settings.remove_overflow) drop_overflow(out, front);
    summary.layers.push_back(out);
    if (finished && settings.layer_done) settings.layer_done(out, bed, state);
    return finished;
  }

  SpreadSummary finish(std::chrono::steady_clock::time_point started) {
    summary.steps = step - (restart ? restart->step : 0);
    summary.sim_time = static_cast<double>(step) * run.dt;
    summary.dt = run.dt;
    summary.max_overlap = largest_overlap(run);
    summary.neighbour_rebuilds = run.rebuilds;
    summary.state = state;
    summary.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    summary.particle_steps_per_s = summary.wall_time > 0 ? particle_steps / summary.wall_time : 0;
    return summary;
  }
};

}  // namespace

SpreadSummary run_spread(bed::Bed& bed, const Scene& scene, const SpreadSettings& settings,
                         const SpreadState* restart) {
  const auto started = std::chrono::steady_clock::now();
  const detail::FlushSubnormals flush;  // resting powder's speeds decay into subnormals
  scene.validate();
  Spreader spread(bed, scene, settings, restart);
  spread.run.box = Box::from(bed.domain);
  check_settings(bed, scene, settings, spread.run.box);
  spread.set_up();
  if (!settings.with_tool) {
    spread.granular();
  } else {
    spread.run.tool_on = true;
    for (std::uint64_t k = 0; k < settings.layers; ++k) {
      if (!spread.layer()) break;  // the observer stopped the run
    }
  }
  return spread.finish(started);
}

}  // namespace powderbed::dem
