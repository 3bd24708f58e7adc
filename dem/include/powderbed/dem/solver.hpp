#pragma once
// DEM drop deposition (docs/physics.md §4): integrates the bed's particles under the scene's effects.
#include <cstdint>
#include <functional>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/rest_criteria.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/bed/option_words.hpp"

namespace powderbed::dem {

enum class Integrator { verlet, rk4 };
inline constexpr bed::OptionWord<Integrator> kIntegratorWords[] = {{"verlet", Integrator::verlet},
                                                                {"rk4", Integrator::rk4}};
// "verlet" | "rk4"; throws InputError naming `option` otherwise.
Integrator parse_integrator(const std::string& text, const std::string& option = "--integrator");

// The lid of the consolidation step ([KE], docs/physics.md §6: "lower the lid onto the bed and release
// it"). After the settle, the box's top face comes down to the highest particle top and moves
// down at `speed` until the bed pushes on it with pressure x (top area) or it has travelled
// `travel` (whichever comes first; at least one must be set), stays there for `hold`, and goes
// back up to the top of the box at `speed`; the bed then relaxes until rest or for `relax` at
// most. The lid is the top face of the box with the walls' contact law (the scene's law with
// R* = r_i, m* = m_i; the approach rate counts its velocity), so it needs effects.walls; it moves
// between steps and costs nothing when off.
struct LidSettings {
  bool enabled = false;
  double speed = 0.01;   // m/s
  double pressure = 0;   // Pa; 0: no force target
  double travel = 0;     // m; 0: no travel limit
  // m; 0: none. Instead of a travel: lower the lid to `depth` below the bed's surface (the 90th
  // percentile of the particle tops z + r, which a few perched particles do not move), i.e.
  // overlap the top layer by `depth` ([KE]'s consolidation: "on the order of the particle
  // radius"); with release, the top boundary is then raised again and the bed relaxes.
  double depth = 0;
  // s. With a pressure the lid holds it while held: it moves at up to `speed` against the force
  // error, v = speed · clamp((F_target − F) / F_target, −1, 1) (a proportional servo, as a
  // stress-controlled wall in DEM codes); with a travel only it holds its position.
  double hold = 0;
  double relax = 0.1;    // s, the cap on the relaxation after the release
  // false: the lid stays where it stopped and the bed's domain ends there, so the bed is
  // written pressed against its top face (keff's hot wall touches it as [KE]'s lid does).
  bool release = true;
};

// The insertion of Kumar Yadav & Eshraghi [KE] 2016 (MFiX-DEM): "particles are injected at
// random positions on the top boundary with an initial velocity" and "added to completely fill
// the domain". With it the bed passed in is the pool: its particles, in order, enter one by one
// at `rate` per second (the first at t = 0), each at a uniform random position in the box's top
// layer (one largest diameter under the top face, inside the side faces, overlapping no particle
// already in), moving down at `speed`. A particle that finds no free spot in `tries` draws waits
// for the next insertion time; the box is full once insertion has failed for `patience` s in a
// row. Insertion then ends, the pool's rest is dropped (the bed shrinks to the inserted
// particles) and the run goes on (t_end / until_rest, then the lid). Rest is not tested while
// particles still enter.
struct InsertionSettings {
  bool enabled = false;
  double rate = 0;           // particles/s
  double speed = 0;          // m/s, downward, >= 0
  std::size_t tries = 100;   // random draws per particle and insertion time
  double patience = 0;       // s; 0: twice the time to fall one largest diameter at `speed`
                             // (the time a new particle needs to clear the layer)
  std::uint64_t seed = 1;
};

struct Progress {
  std::uint64_t step = 0;
  double time = 0;      // simulated, s
  double t_end = 0;     // s (with until_rest: the cap)
  double kinetic_energy = 0;
  double max_speed = 0;
};

struct RunSettings {
  Integrator integrator = Integrator::verlet;
  double dt = 0;                // s; 0 = TimeStepBound::recommended
  bool unsafe_dt = false;       // accept dt above TimeStepBound::stable
  double young_scale = 1;       // E used = E / young_scale (particles and walls; Hertz law only)
  double t_end = 0;             // s; with until_rest the cap on simulated time (0: 1 s)
  bool until_rest = false;
  RestCriteria rest;
  // Verlet skin, m; 0: the engine's default, 0.5 x the largest radius (narrowed on a narrow
  // periodic axis; spread.hpp), or 0.1 x the largest diameter on the drop solver (RK4)
  double skin = 0;
  int threads = 0;              // OpenMP threads; 0 = OpenMP's default
  // Beds with fewer particles run on one thread whatever `threads` says: a step of the 600-
  // particle [GZ] bed is ~20 us of work in ~5 parallel loops, and each fork/barrier costs
  // microseconds on an idle machine and far more on a busy one (measured on the shared 2-core
  // machine: 0.5 s on 1 thread, 13 s on 2 for 20,000 steps; docs/results/deposit-speed.md).
  std::size_t parallel_min_particles = 4096;
  std::string trajectory;       // HDF5 time series path ("" = none), with an XDMF sidecar
  std::uint64_t trajectory_every = 0;  // steps between snapshots (> 0 with a trajectory)
  // Called every progress_every steps (and at the end) when set.
  std::function<void(const Progress&)> progress;
  std::uint64_t progress_every = 2000;
  // Called after every observe_every-th step with the current bed (positions and velocities
  // up to date); returning true stops the run. For tests and diagnostics.
  std::function<bool(std::uint64_t step, double time, const bed::Bed& bed)> observer;
  std::uint64_t observe_every = 1;
  // The thermo table (diagnostics.hpp ThermoRow), when set: a row at step 0, every thermo_every
  // steps (0: thermo_interval of the settle's steps, t_end or the until_rest cap) and at the
  // run's last step. It reads the state only, so a run gives the same bed with or without it;
  // unset, it costs nothing.
  ThermoFn thermo;
  std::uint64_t thermo_every = 0;
  LidSettings lid;
  InsertionSettings insertion;
};

struct LidSummary {
  double start_z = 0;          // m: the lid when it began to move (highest particle top)
  double surface_z = 0;        // m: the bed's surface (with a depth; LidSettings::depth)
  double stop_z = 0;           // m: where it stopped (its lowest position)
  double target_force = 0;     // N: pressure x top area (0 without a pressure)
  double stop_force = 0;       // N: force of the bed on the lid when it stopped
  double max_force = 0;        // N: largest force on the lid (lowering and hold)
  double hold_end_force = 0;   // N: force at the end of the hold
  double hold_end_z = 0;       // m: where the lid is at the end of the hold
  double hold_late_force = 0;  // N: mean force over the second half of the hold
  // How the lowering ended: "force" (target reached), "travel", "depth", or "floor" (the lid came within
  // one smallest diameter of the floor with neither reached).
  std::string stopped_by;
  bool released = false;       // raised at the end (LidSettings::release), else kept as the top face
  double release_time = 0;     // s: simulated time the raise began
};

struct RunSummary {
  std::size_t n = 0;
  std::uint64_t steps = 0;
  double sim_time = 0;             // s
  double wall_time = 0;            // s
  double particle_steps_per_s = 0;
  double dt = 0, dt_stable = 0;    // s
  const char* dt_limited_by = "none";  // TimeStepBound::limited_by
  double dt_limiting_radius = 0;       // m, TimeStepBound::limiting_radius
  double kinetic_energy = 0;       // J, at the end (physical masses)
  double max_speed = 0;            // m/s, at the end
  double max_overlap = 0;          // largest overlap / smaller radius (pairs and walls), at end
  double max_overlap_m = 0;        // the same overlap in m
  // What that overlap would be at full stiffness under the same force: Hertz force goes as
  // E delta^{3/2}, so delta_full = delta_soft * young_scale^{-2/3}; with the linear law the
  // Hertz overlap at the materials' E* under k_n delta.
  double max_overlap_full_stiffness = 0;
  std::size_t lost = 0;            // particles whose centre left the box (non-periodic axes)
  bool at_rest = false;
  std::uint64_t neighbour_rebuilds = 0;
  std::size_t inserted = 0;        // with insertion: particles that entered
  double insertion_end = 0;        // s: when insertion ended
  // "full" (no free spot for `patience` s), "pool" (every particle in) or "time" (t_end first)
  std::string insertion_stopped_by;
  bool lid_used = false;
  LidSummary lid;               // when lid_used; at_rest then says whether the relaxation ended at rest
};

// Throws InputError for settings out of range: t_end < 0 (or 0 without until_rest), dt < 0,
// a negative skin, trajectory_every 0 with a trajectory, rest criteria out of range. Run by
// run_deposition; for callers that hand the settings to another solver (deposit's rotating drop).
void check_run_settings(const RunSettings& settings);

// Integrates the bed in place (positions and velocities; velocities are created at zero when
// the bed has none; with settings.insertion the bed is the pool of InsertionSettings), then,
// with settings.lid.enabled, consolidates it with the lid. The
// domain's periodic x/y flags make those axes periodic. Throws InputError for a bad
// scene/settings (dt above the stable bound without unsafe_dt, a particle centre outside the
// domain, a 2D bed, a periodic axis shorter than 3 neighbour cells, a lid without
// effects.walls, with neither pressure nor travel or a non-positive speed) and NumericalError
// naming the particle id and step when the state goes non-finite. Deterministic: the same
// input gives bit-identical output for any thread count. A drop with velocity Verlet runs on
// the one engine (dem/src/engine.hpp, the spreading engine without a tool), which also carries
// the laws that need particle rotation (friction.model = history, material.rolling > 0); RK4
// still runs on the drop solver, which refuses those laws.
RunSummary run_deposition(bed::Bed& bed, const Scene& scene, const RunSettings& settings);

// Removes particles whose centre lies outside the domain on a non-periodic axis; returns how
// many were removed.
std::size_t remove_lost_particles(bed::Bed& bed);

}  // namespace powderbed::dem
