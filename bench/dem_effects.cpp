// What each effect of a deposition scene costs per step, and what an effect switched off costs
// (docs/architecture.md "Effects a scene calls for"). run_deposition runs on the engine
// (dem/src/engine.hpp), whose contact is composed once per run and whose batch kernel is compiled
// for damping and friction (contact_kernel.hpp); gravity and drag act in the drift pass with
// their coefficients (0 when off) and the walls' candidates are found at each prune. Three
// benchmark families on the same beds, one thread, E = 193 GPa:
//   BM_Step/<mask>: steps with the effects of <mask> on (kAllEffects, then each bit off in turn);
//   BM_StepZeroed/<effect>: all bits on but that effect's coefficient set to 0 (mu_d = 0,
//     zeta = 0, g = 0): the effect's code runs and adds nothing, which is what a run-time switch
//     in the inner loop would cost. Bit off vs zeroed is the saving of compiling the effect out;
//     bit off vs all on is the effect's cost;
//   BM_Engine/<engine>/<bed>: every effect on, the whole run (set-up included) on the engine
//     through run_deposition (0, the drop's model: particles that do not turn, its pairs and
//     faces batched), through run_spread without a tool and without rotation (1, the same
//     model) or with the spread's rotating model (2). The drop solver that BM_Engine/0 ran
//     until issue 33 deleted it: docs/results/deposit-engine-ab.md.
// Beds: FCC stacks of spheres of radius 13.5 um (the [GZ] mean) compressed by 0.1 % so every
// neighbour touches (12 contacts per interior sphere), resting on the floor and touching the
// side walls: 600 (5 x 5 x 6 cells) and 19,652 (17^3 cells) particles. The timer runs from the
// end of the first step to the end of the last (the run's set-up and list build left out).
// Run: build/bench/bench_dem_effects [--benchmark_repetitions=3 --benchmark_report_aggregates_only=true]
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/dem/time_step.hpp"

namespace pb = powderbed::bed;
namespace dem = powderbed::dem;

namespace {

constexpr double kRadius = 13.5e-6;
constexpr double kCompression = 1e-3;

// nx x ny x nz conventional FCC cells of touching spheres, shrunk by kCompression; the box
// encloses them with the same overlap at the floor and side walls, and room above.
pb::Bed fcc_stack(int nx, int ny, int nz) {
  const double a = 2.0 * std::sqrt(2.0) * kRadius * (1.0 - kCompression);
  const double inset = kRadius * (1.0 - kCompression);  // overlap with the walls
  static const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  pb::Bed bed;
  bed.domain.upper = {(nx - 0.5) * a + 2 * inset, (ny - 0.5) * a + 2 * inset, (nz + 1) * a};
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        for (const auto& b : basis) {
          const double x = (i + b[0]) * a + inset, y = (j + b[1]) * a + inset,
                       z = (k + b[2]) * a + inset;
          bed.id.push_back(bed.n());
          bed.x.push_back(x);
          bed.y.push_back(y);
          bed.z.push_back(z);
          bed.radius.push_back(kRadius);
        }
      }
    }
  }
  return bed;
}

const pb::Bed& small_bed() {
  static const pb::Bed bed = fcc_stack(5, 5, 6);
  return bed;
}
const pb::Bed& large_bed() {
  static const pb::Bed bed = fcc_stack(17, 17, 17);
  return bed;
}

// Times `steps` steps (less the first) of `scene` on a copy of `bed`, at the all-effects step.
void run_steps(benchmark::State& state, const pb::Bed& bed, const dem::Scene& scene, int steps) {
  dem::Scene full;
  const double dt = dem::time_step_bound(bed, full, 1.0).recommended;
  dem::RunSettings settings;
  settings.dt = dt;
  settings.unsafe_dt = true;  // masks without hertz/walls have other bounds: one dt for all
  settings.t_end = steps * dt;
  settings.threads = 1;
  using Clock = std::chrono::steady_clock;
  Clock::time_point first;
  double seconds = 0, total = 0;
  settings.observer = [&](std::uint64_t step, double, const pb::Bed&) {
    if (step == 1) first = Clock::now();
    if (step == static_cast<std::uint64_t>(steps)) {
      seconds = std::chrono::duration<double>(Clock::now() - first).count();
    }
    return false;
  };
  for (auto _ : state) {
    pb::Bed copy = bed;
    const dem::RunSummary summary = dem::run_deposition(copy, scene, settings);
    benchmark::DoNotOptimize(summary.kinetic_energy);
    state.SetIterationTime(seconds);
    total += seconds;
  }
  const double particle_steps = static_cast<double>(bed.n()) * (steps - 1);
  state.counters["n"] = static_cast<double>(bed.n());
  state.counters["ns_per_particle_step"] =
      total * 1e9 / (particle_steps * static_cast<double>(state.iterations()));
}

// range(0): effect mask; range(1): 0 small bed, 1 large bed.
void BM_Step(benchmark::State& state) {
  dem::Scene scene;
  scene.effects = static_cast<unsigned>(state.range(0));
  const bool large = state.range(1) != 0;
  run_steps(state, large ? large_bed() : small_bed(), scene, large ? 100 : 2000);
}

// range(0): the effect whose coefficient is zeroed (bit kept on); range(1) as BM_Step.
void BM_StepZeroed(benchmark::State& state) {
  dem::Scene scene;
  const auto effect = static_cast<unsigned>(state.range(0));
  if (effect == dem::kFriction) scene.material.friction = 0;
  if (effect == dem::kDamping) scene.material.damping = 0;
  if (effect == dem::kGravity) scene.gravity = 0;
  const bool large = state.range(1) != 0;
  run_steps(state, large ? large_bed() : small_bed(), scene, large ? 100 : 2000);
}

// The spread's own contact model on the default scene: history friction and rolling
// resistance (data/scenes/spread-blade.ini's), particles that turn.
dem::Scene rotating_scene() {
  dem::Scene scene;
  scene.friction_model = dem::FrictionModel::history;
  scene.material.rolling = 0.1;
  return scene;
}

// range(0): 0 drop solver, 1 spreading engine with the drop's model, 2 spreading engine with
// history friction and rolling (rotating_scene); range(1) as BM_Step. Times the runs' own wall
// clocks (set-up and list build included, the same work on both).
void BM_Engine(benchmark::State& state) {
  const dem::Scene scene = state.range(0) == 2 ? rotating_scene() : dem::Scene{};
  const bool large = state.range(1) != 0;
  const pb::Bed& bed = large ? large_bed() : small_bed();
  const int steps = large ? 100 : 2000;
  const double dt = dem::time_step_bound(bed, scene, 1.0).recommended;
  double total = 0;
  for (auto _ : state) {
    pb::Bed copy = bed;
    double seconds = 0;
    if (state.range(0) == 0) {
      dem::RunSettings settings;
      settings.dt = dt;
      settings.t_end = steps * dt;
      settings.threads = 1;
      seconds = dem::run_deposition(copy, scene, settings).wall_time;
    } else {
      dem::SpreadSettings settings;
      settings.with_tool = false;
      settings.rotation = state.range(0) == 2;
      settings.dt = dt;
      settings.t_end = steps * dt;
      settings.threads = 1;
      seconds = dem::run_spread(copy, scene, settings).wall_time;
    }
    benchmark::DoNotOptimize(copy.z.data());
    state.SetIterationTime(seconds);
    total += seconds;
  }
  state.counters["n"] = static_cast<double>(bed.n());
  state.counters["ns_per_particle_step"] =
      total * 1e9 / (static_cast<double>(bed.n()) * steps * static_cast<double>(state.iterations()));
}

void step_masks(benchmark::internal::Benchmark* b) {
  for (const int bed : {0, 1}) {
    b->Args({dem::kAllEffects, bed});
    for (unsigned bit = 0; bit < dem::kEffectCount; ++bit) {
      b->Args({static_cast<long>(dem::kAllEffects & ~(1u << bit)), bed});
    }
  }
}

void zeroed_effects(benchmark::internal::Benchmark* b) {
  for (const int bed : {0, 1}) {
    for (const unsigned effect : {dem::kFriction, dem::kDamping, dem::kGravity}) {
      b->Args({effect, bed});
    }
  }
}

BENCHMARK(BM_Step)->Apply(step_masks)->UseManualTime()->Unit(benchmark::kMicrosecond)->MinTime(0.2);
BENCHMARK(BM_Engine)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.5);
BENCHMARK(BM_StepZeroed)
    ->Apply(zeroed_effects)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(0.2);

}  // namespace

BENCHMARK_MAIN();
