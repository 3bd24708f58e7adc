// What each sinter effect costs (docs/architecture.md "Effects a scene calls for": an effect that is off
// costs nothing in the inner loop). The solver picks one of 64 particle kernels compiled for
// the chosen effects and a grid kernel for constant or variable conductivity, so switching an
// effect off removes its work rather than skipping it per contact. Two beds:
// - particles: 20,000 spheres on a 3 x 3 x 3-node substrate (the particle step dominates);
// - grid: no particles on 101 x 51 x 31 nodes (the grid step dominates);
// - implicit: 2,500 spheres on 41 x 21 x 11 nodes under backward Euler, whose matrix assembly
//   composes conduction, the surface losses and the laser on the substrate the same way.
// Each benchmark runs 20 grid steps of the solver with the effects named in its label.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/material.hpp"
#include "powderbed/thermal/scene.hpp"
#include "powderbed/thermal/solver.hpp"

namespace {

using namespace powderbed;

// A square array of touching-and-overlapping spheres resting on the floor: every particle has
// four neighbours and a floor contact.
bed::Bed lattice_bed(int side) {
  const double r = 10e-6, spacing = 1.98 * r;
  bed::Bed bed;
  bed.domain.lower = {0, 0, 0};
  bed.domain.upper = {spacing * side + 2 * r, spacing * side + 2 * r, 4 * r};
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i)
      bed.add(r + spacing * i, r + spacing * j, r * (1 - 1e-3), r);
  return bed;
}

const thermal::MaterialTable& table() {
  static const thermal::MaterialTable t =
      thermal::read_material_table(POWDERBED_SOURCE_DIR "/data/materials/316L.csv");
  return t;
}

// Times 20 grid steps of `bed` under `scene` (its step, unless set, the scene's stable default).
void time_steps(benchmark::State& state, const bed::Bed& bed, thermal::SinterScene scene,
                std::int64_t items_per_step) {
  scene.laser_y = 0.5 * bed.domain.length(1);
  scene.start_x = 0;
  scene.speed = 1e-6;  // the beam stays on the bed
  scene.t_end = 1;
  if (!(scene.dt > 0)) scene.dt = thermal::Sinter(bed, scene, table()).dt();
  scene.t_end = 20 * scene.dt;
  for (auto _ : state) {
    state.PauseTiming();
    thermal::Sinter sinter(bed, scene, table());
    state.ResumeTiming();
    sinter.run(nullptr, 0, nullptr);
  }
  state.SetItemsProcessed(state.iterations() * 20 * items_per_step);
}

void particles(benchmark::State& state, unsigned effects_off) {
  static const bed::Bed bed = lattice_bed(141);
  thermal::SinterScene scene;
  scene.absorption = thermal::LaserAbsorption::beer_lambert;  // the kernels of [GZ]'s model
  scene.nodes = {3, 3, 3};
  scene.effects = thermal::kAllSinterEffects & ~effects_off;
  time_steps(state, bed, scene, static_cast<std::int64_t>(bed.n()));
}

void grid(benchmark::State& state, unsigned effects_off) {
  bed::Bed bed;
  bed.domain.lower = {0, 0, 0};
  bed.domain.upper = {0.5e-3, 0.25e-3, 0.1e-3};
  thermal::SinterScene scene;
  scene.absorption = thermal::LaserAbsorption::beer_lambert;
  scene.nodes = {101, 51, 31};
  scene.substrate_depth = 0.15e-3;
  scene.effects = thermal::kAllSinterEffects & ~effects_off;
  time_steps(state, bed, scene, 101 * 51 * 31);
}

// Backward Euler at 1e-5 s, a few times the explicit bound of this grid (as
// tests/thermal/test_substrate.cpp steps it); wetting works with the explicit integrator only.
void implicit(benchmark::State& state, unsigned effects_off) {
  static const bed::Bed bed = lattice_bed(50);
  thermal::SinterScene scene;
  scene.absorption = thermal::LaserAbsorption::beer_lambert;
  scene.integrator = thermal::Integrator::implicit_euler;
  scene.nodes = {41, 21, 11};
  scene.dt = 1e-5;
  scene.effects = thermal::kAllSinterEffects & ~effects_off;
  time_steps(state, bed, scene, static_cast<std::int64_t>(bed.n() + 41 * 21 * 11));
}

}  // namespace

BENCHMARK_CAPTURE(particles, all_effects, 0u)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(particles, no_conduction, thermal::kConduction)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(particles, no_substrate_contact, thermal::kSubstrateContact)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(particles, no_radiation, thermal::kRadiation)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(particles, no_convection_no_radiation, thermal::kConvection | thermal::kRadiation)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(particles, no_laser, thermal::kLaser)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(particles, no_variable_properties, thermal::kVariableProperties)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(particles, only_laser,
                  thermal::kAllSinterEffects & ~(thermal::kLaser | thermal::kPenetration))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grid, all_effects, 0u)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(grid, constant_properties, thermal::kVariableProperties)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(implicit, all_effects, 0u)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(implicit, constant_properties, thermal::kVariableProperties)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(implicit, no_laser_substrate, thermal::kLaserSubstrate)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
