#pragma once
// DEM drop deposition (SPEC.md §4): integrates the bed's particles under the scene's effects.
#include <cstdint>
#include <functional>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::dem {

enum class Integrator { verlet, rk4 };
// "verlet" | "rk4"; throws InputError naming `option` otherwise.
Integrator parse_integrator(const std::string& text, const std::string& option = "--integrator");

// The bed is at rest when, at every check during `window` seconds of simulated time, the
// largest speed is below max_speed and the kinetic energy below kinetic_energy.
struct RestCriteria {
  double max_speed = 1e-4;        // m/s
  double kinetic_energy = 0;      // J; 0 means 1e-2 * (1/2) M max_speed^2 (M the bed's mass),
                                  // i.e. an RMS speed of 10 % of max_speed
  double window = 1e-3;           // s
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
  double young_scale = 1;       // E used = E / young_scale (particles and walls)
  double t_end = 0;             // s; with until_rest the cap on simulated time (0: 1 s)
  bool until_rest = false;
  RestCriteria rest;
  double skin = 0;              // Verlet skin, m; 0 = 0.1 * largest diameter
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
};

struct RunSummary {
  std::size_t n = 0;
  std::uint64_t steps = 0;
  double sim_time = 0;             // s
  double wall_time = 0;            // s
  double particle_steps_per_s = 0;
  double dt = 0, dt_stable = 0;    // s
  double kinetic_energy = 0;       // J, at the end
  double max_speed = 0;            // m/s, at the end
  double max_overlap = 0;          // largest overlap / smaller radius (pairs and walls), at end
  double max_overlap_m = 0;        // the same overlap in m
  // What that overlap would be at full stiffness under the same force: Hertz force goes as
  // E delta^{3/2}, so delta_full = delta_soft * young_scale^{-2/3}.
  double max_overlap_full_stiffness = 0;
  std::size_t lost = 0;            // particles whose centre left the box (non-periodic axes)
  bool at_rest = false;
  std::uint64_t neighbour_rebuilds = 0;
};

// Integrates the bed in place (positions and velocities; velocities are created at zero when
// the bed has none). The domain's periodic x/y flags make those axes periodic. Throws
// InputError for a bad scene/settings (dt above the stable bound without unsafe_dt, a particle
// centre outside the domain, a 2D bed, a periodic axis shorter than 3 neighbour cells) and
// NumericalError naming the particle id and step when the state goes non-finite. Deterministic:
// the same input gives bit-identical output for any thread count.
RunSummary run_deposition(bed::Bed& bed, const Scene& scene, const RunSettings& settings);

// Removes particles whose centre lies outside the domain on a non-periodic axis; returns how
// many were removed.
std::size_t remove_lost_particles(bed::Bed& bed);

}  // namespace powderbed::dem
