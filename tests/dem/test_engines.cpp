// The two DEM engines on the drop's scenarios (issue 33: one engine, the other deleted once this
// holds for every scenario): the spreading engine with particles that do not turn
// (SpreadSettings::rotation false) against the drop solver, at the same step. They sum the
// forces in different orders (the drop: walls by face, then pairs; the spread: plate, top,
// sides, then pairs) and take the Verlet half kicks apart or merged, so they agree to rounding
// at first and drift apart as collisions amplify the difference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "beds.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"

using namespace powderbed;

namespace {

struct Scenario {
  std::string name;
  unsigned effects;
  dem::ContactLaw law;
  std::size_t particles;
  double t_end;     // s
  double tolerance; // largest |x_drop - x_spread| over all particles and axes / smallest radius
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

bed::Bed on_drop_solver(const Scenario& s) {
  bed::Bed b = bed_of(s);
  dem::RunSettings run;
  run.t_end = s.t_end;
  run.dt = kDt;
  run.young_scale = s.law == dem::ContactLaw::hertz ? 1e3 : 1.0;
  dem::run_deposition(b, scene_of(s), run);
  return b;
}

bed::Bed on_spreading_engine(const Scenario& s) {
  bed::Bed b = bed_of(s);
  dem::SpreadSettings run;
  run.with_tool = false;
  run.rotation = false;
  run.t_end = s.t_end;
  run.dt = kDt;
  run.young_scale = s.law == dem::ContactLaw::hertz ? 1e3 : 1.0;
  dem::run_spread(b, scene_of(s), run);
  return b;
}

class Engines : public ::testing::TestWithParam<Scenario> {};

TEST_P(Engines, SpreadingEngineWithoutRotationIsTheDropSolver) {
  const Scenario& s = GetParam();
  const bed::Bed drop = on_drop_solver(s), spread = on_spreading_engine(s);
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

// Each of the drop's effects over the walls (the spreading engine's plate is a wall, so it
// always has them), then all of them with either law, on a column of six particles that land on
// the floor and on each other within the run; then forty with every effect. Both engines start
// equal to rounding, and each contact that begins or ends amplifies the difference: with
// damping the column's worst difference was 8e-12 of a radius at 5e-4 s, 1e-9 at 7e-4 s,
// 2e-7 at 1.2e-3 s and 6e-6 at 1.5e-3 s, a single particle's 0 at any time. The runs stop
// while it is small, and the tolerance, 1e-7 of a radius, is some hundred times what they
// measured; a law that differed would be off by its own size at the first contact.
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
        Scenario{"many_linear", dem::kAllEffects, dem::ContactLaw::linear, 40, 2e-4, 1e-7}),
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
