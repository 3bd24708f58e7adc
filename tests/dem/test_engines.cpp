// The drop's scenarios on the engine (issue 33: one engine) against what the drop solver, the
// engine that ran the drops before, gave for them: run_deposition (dem/src/engine.hpp through
// drop_on_engine.cpp) against tests/data/drop_solver/<scenario>.csv, the drop solver's
// positions at the run's end (and its step count, particles inserted and the lid's largest
// force), written by dem::detail::run_on_drop_solver at commit cceef59 before it was deleted;
// each effect, both laws, RK4, the lid and insertion, at the same step. The two sum the forces
// in different orders (the drop solver: walls by face, then pairs; the engine: plate, top,
// sides, then pairs) and took the Verlet half kicks apart or merged, so they agree to rounding
// at first and drift apart as collisions amplify the difference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "beds.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"

using namespace powderbed;

namespace {

enum class Driver { verlet, rk4, lid, insertion };

struct Scenario {
  std::string name;
  unsigned effects;
  dem::ContactLaw law;
  std::size_t particles;
  double t_end;     // s
  double tolerance; // largest |x_drop - x_spread| over all particles and axes / smallest radius
  Driver driver = Driver::verlet;
};

constexpr double kSmall = 10e-6, kLarge = 20e-6;  // radii, m
constexpr double kDt = 2e-8;                      // s, both engines

dem::Scene scene_of(const Scenario& s) {
  dem::Scene scene = test::scene_with(s.effects);
  scene.law = s.law;
  scene.stiffness = 50.0;  // N/m: the linear law's k_n (a Rayleigh-like step well above kDt)
  scene.gravity = 1e3;     // brings the particles together within the short run
  return scene;
}

// Up to six particles: a column, each a little off the axis of the one under it, so that they
// land on each other; more: scattered at random.
bed::Bed bed_of(const Scenario& s) {
  bed::Bed b = test::box_bed(2e-4, 2e-4, 4e-4);
  if (s.particles <= 6) {
    for (std::size_t k = 0; k < s.particles; ++k) {
      const double side = k % 2 == 0 ? 1.0 : -1.0, step = static_cast<double>(k);
      b.add(1e-4 + side * 4e-6 * step, 1e-4 + 3e-6 * step, 30e-6 + 50e-6 * step, k % 2 == 0 ? kLarge : kSmall);
    }
    return b;
  }
  const double lo[3] = {0, 0, 0}, hi[3] = {2e-4, 2e-4, 2e-4};
  test::add_random(b, s.particles, kSmall, kLarge, lo, hi, 11);
  return b;
}

dem::RunSettings settings_of(const Scenario& s) {
  dem::RunSettings run;
  run.t_end = s.t_end;
  run.dt = kDt;
  run.young_scale = s.law == dem::ContactLaw::hertz ? 1e3 : 1.0;
  if (s.driver == Driver::rk4) run.integrator = dem::Integrator::rk4;
  if (s.driver == Driver::lid) {  // lowered at once 10 um into the column's top, held, released
    run.lid.enabled = true;
    run.lid.speed = 1;
    run.lid.travel = 1e-5;
    run.lid.hold = 2e-5;
    run.lid.relax = 5e-5;
  }
  if (s.driver == Driver::insertion) {  // the pool enters within the first 4e-4 s
    run.insertion.enabled = true;
    run.insertion.rate = 1e5;
    run.insertion.speed = 0.5;
    run.insertion.seed = 5;
  }
  return run;
}

struct Outcome {
  bed::Bed bed;
  dem::RunSummary summary;
};

// The drop solver's end of the scenario (tests/data/drop_solver, see the top of this file).
Outcome on_drop_solver(const Scenario& s) {
  const std::string path = std::string(POWDERBED_TEST_DATA) + "/drop_solver/" + s.name + ".csv";
  std::ifstream in(path);
  Outcome o{bed_of(s), {}};
  std::string tag, header;
  unsigned long long steps = 0, inserted = 0;
  in >> tag >> tag >> steps >> tag >> inserted >> tag >> o.summary.lid.max_force >> header;
  o.summary.steps = steps;
  o.summary.inserted = inserted;
  std::vector<double> x, y, z;
  char comma;
  double a, b, c;
  while (in >> a >> comma >> b >> comma >> c) {
    x.push_back(a);
    y.push_back(b);
    z.push_back(c);
  }
  EXPECT_EQ(header, "x,y,z") << path;
  o.bed.x = x;
  o.bed.y = y;
  o.bed.z = z;
  o.bed.radius.resize(x.size());  // n(): the particles at the end (with insertion, those in)
  return o;
}

Outcome on_engine(const Scenario& s) {
  Outcome o{bed_of(s), {}};
  o.summary = dem::run_deposition(o.bed, scene_of(s), settings_of(s));
  return o;
}

class Engines : public ::testing::TestWithParam<Scenario> {};

TEST_P(Engines, TheEngineRunsTheDropSolversScenarios) {
  const Scenario& s = GetParam();
  const Outcome old_run = on_drop_solver(s), new_run = on_engine(s);
  const bed::Bed &drop = old_run.bed, &spread = new_run.bed;
  EXPECT_EQ(old_run.summary.steps, new_run.summary.steps) << s.name;
  EXPECT_EQ(old_run.summary.inserted, new_run.summary.inserted) << s.name;
  if (s.driver == Driver::lid) {  // the lid pressed the column, with the same force
    EXPECT_GT(old_run.summary.lid.max_force, 0) << s.name;
    EXPECT_NEAR(new_run.summary.lid.max_force, old_run.summary.lid.max_force, 1e-9 * old_run.summary.lid.max_force);
  }
  ASSERT_EQ(drop.n(), spread.n());
  double worst = 0, moved = 0;
  const bed::Bed start = bed_of(s);
  for (std::size_t i = 0; i < drop.n(); ++i) {
    worst = std::max({worst, std::abs(drop.x[i] - spread.x[i]), std::abs(drop.y[i] - spread.y[i]),
                      std::abs(drop.z[i] - spread.z[i])});
    moved = std::max(moved, std::abs(drop.z[i] - start.z[i]));
  }
  EXPECT_LE(worst / kSmall, s.tolerance) << s.name;
  EXPECT_GT(moved, kSmall) << s.name << ": the scene must move for the comparison to mean something";
}

// Each of the drop's effects over the walls (the engine's plate is a wall, so it always has
// them), then all of them with either law, on a column of six particles that land on
// the floor and on each other within the run; then forty with every effect. Both engines start
// equal to rounding, and each contact that begins or ends amplifies the difference: with
// damping the column's worst difference was 8e-12 of a radius at 5e-4 s, 1e-9 at 7e-4 s,
// 2e-7 at 1.2e-3 s and 6e-6 at 1.5e-3 s, a single particle's 0 at any time. The runs stop
// while it is small, and the tolerance, 1e-7 of a radius, is some hundred times what they
// measured; a law that differed would be off by its own size at the first contact. Measured when
// the drops moved onto the engine (worst / smallest radius): walls 1e-11, drag 6e-13, pairs
// 3e-11, damping 4e-9, friction 4e-9, all_hertz 1.1e-8, all_linear 9e-11, many_hertz 4e-13,
// many_linear 5e-14, rk4_hertz 6e-10, rk4_linear 5e-11, insertion (40 particles entering from the
// top) 3e-13; the lid, lowered 10 um into the standing column's top at 1 m/s, held and
// released, presses it with the same force (8.9e-5 N) on both.
INSTANTIATE_TEST_SUITE_P(
    DropScenarios, Engines,
    ::testing::Values(
        Scenario{"walls", dem::kGravity | dem::kWalls, dem::ContactLaw::hertz, 6, 8e-4, 1e-7},
        Scenario{"drag", dem::kGravity | dem::kDrag | dem::kWalls, dem::ContactLaw::hertz, 6, 8e-4, 1e-7},
        Scenario{"pairs", dem::kGravity | dem::kHertz | dem::kWalls, dem::ContactLaw::hertz, 6, 8e-4, 1e-7},
        Scenario{"damping", dem::kGravity | dem::kHertz | dem::kWalls | dem::kDamping, dem::ContactLaw::hertz,
                 6, 8e-4, 1e-7},
        Scenario{"friction", dem::kGravity | dem::kHertz | dem::kWalls | dem::kFriction, dem::ContactLaw::hertz,
                 6, 8e-4, 1e-7},
        Scenario{"all_hertz", dem::kAllEffects, dem::ContactLaw::hertz, 6, 8e-4, 1e-7},
        Scenario{"all_linear", dem::kAllEffects, dem::ContactLaw::linear, 6, 8e-4, 1e-7},
        Scenario{"many_hertz", dem::kAllEffects, dem::ContactLaw::hertz, 40, 3e-4, 1e-7},
        Scenario{"many_linear", dem::kAllEffects, dem::ContactLaw::linear, 40, 2e-4, 1e-7},
        Scenario{"rk4_hertz", dem::kAllEffects, dem::ContactLaw::hertz, 6, 8e-4, 1e-7, Driver::rk4},
        Scenario{"rk4_linear", dem::kAllEffects, dem::ContactLaw::linear, 6, 8e-4, 1e-7, Driver::rk4},
        Scenario{"lid", dem::kAllEffects, dem::ContactLaw::hertz, 6, 2e-6, 1e-7, Driver::lid},
        Scenario{"insertion", dem::kAllEffects, dem::ContactLaw::hertz, 40, 3e-4, 1e-7, Driver::insertion}),
    [](const ::testing::TestParamInfo<Scenario>& p) { return p.param.name; });

// Particles that do not turn cannot carry the laws that turn them.
TEST(Engines, WithoutRotationHistoryFrictionAndRollingAreRefused) {
  const Scenario s{"refused", dem::kAllEffects, dem::ContactLaw::hertz, 2, 1e-5, 0};
  for (const bool rolling : {false, true}) {
    dem::Scene scene = scene_of(s);
    if (rolling) {
      scene.material.rolling = 0.1;
    } else {
      scene.friction_model = dem::FrictionModel::history;
    }
    bed::Bed b = bed_of(s);
    dem::SpreadSettings run;
    run.with_tool = false;
    run.rotation = false;
    run.t_end = s.t_end;
    try {
      dem::run_spread(b, scene, run);
      ADD_FAILURE() << (rolling ? "rolling" : "history") << " accepted without rotation";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(rolling ? "material.rolling" : "friction.model"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
