// The consolidation lid (solver.hpp LidSettings, issue 6 "Beds for it") on a small settled bed,
// and the core density it is judged by.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "beds.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/stats.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/solver.hpp"

using namespace powderbed;

namespace {

constexpr double kRadius = 0.25e-3;  // m
constexpr double kSide = 2.5e-3;     // box side (5 diameters), m

// 80 spheres of r = 0.25 mm dropped from random non-overlapping positions into a 2.5 mm x 2.5 mm
// box, 6 mm tall: ~4 layers after the settle.
bed::Bed drop_bed() {
  bed::Bed b = test::box_bed(kSide, kSide, 6e-3);
  const double lo[3] = {0, 0, 0}, hi[3] = {kSide, kSide, 6e-3};
  test::add_random(b, 80, kRadius, kRadius, lo, hi, 11);
  return b;
}

dem::Scene lid_scene() {
  dem::Scene scene;  // every effect on, 316L defaults
  scene.material.friction = 0.3;
  scene.material.damping = 0.5;  // settles in tens of ms
  return scene;
}

// Settled until rest (capped at 0.5 s); S = 1e4 softening makes the step ~1e-5 s, so a run is a
// few 1e4 steps of 80 particles (well under a second).
dem::RunSettings settle_settings() {
  dem::RunSettings s;
  s.young_scale = 1e4;
  s.until_rest = true;
  s.t_end = 0.5;
  s.rest.max_speed = 1e-3;
  s.rest.window = 5e-3;
  return s;
}

bool same_state(const bed::Bed& a, const bed::Bed& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z && a.vx == b.vx && a.vy == b.vy && a.vz == b.vz;
}

}  // namespace

TEST(Lid, OffLeavesTheRunBitIdentical) {
  const dem::Scene scene = lid_scene();
  bed::Bed plain = drop_bed(), off = drop_bed(), on = drop_bed();
  const dem::RunSettings s = settle_settings();
  const auto r_plain = dem::run_deposition(plain, scene, s);
  // Lid settings filled in but not enabled: nothing may change.
  dem::RunSettings s_off = s;
  s_off.lid.pressure = 1e3;
  s_off.lid.travel = 1e-3;
  s_off.lid.hold = 1e-3;
  const auto r_off = dem::run_deposition(off, scene, s_off);
  EXPECT_FALSE(r_off.lid_used);
  EXPECT_EQ(r_off.steps, r_plain.steps);
  EXPECT_TRUE(same_state(off, plain));
  // With the lid on, the settle before it is the same run, step for step.
  dem::RunSettings s_on = s_off;
  s_on.lid.enabled = true;
  bool compared = false;
  s_on.observer = [&](std::uint64_t step, double, const bed::Bed& b) {
    if (step == r_plain.steps) {
      EXPECT_TRUE(same_state(b, plain));
      compared = true;
    }
    return false;
  };
  const auto r_on = dem::run_deposition(on, scene, s_on);
  EXPECT_TRUE(compared);
  EXPECT_TRUE(r_on.lid_used);
  EXPECT_GT(r_on.steps, r_plain.steps);
}

TEST(Lid, StopsAtTheTargetForceAndDensifiesTheBed) {
  const dem::Scene scene = lid_scene();
  bed::Bed before = drop_bed(), after = drop_bed();
  dem::RunSettings s = settle_settings();
  const auto settled = dem::run_deposition(before, scene, s);
  ASSERT_TRUE(settled.at_rest);
  const double pressure = 2e3;  // Pa: ~8x the bed's own weight per area (~250 Pa)
  s.lid.enabled = true;
  s.lid.pressure = pressure;
  s.lid.speed = 5e-3;  // m/s
  s.lid.hold = 0.02;
  s.lid.relax = 0.2;
  const auto r = dem::run_deposition(after, scene, s);
  ASSERT_TRUE(r.lid_used);
  EXPECT_EQ(r.lid.stopped_by, "force");
  const double target = pressure * kSide * kSide;
  EXPECT_DOUBLE_EQ(r.lid.target_force, target);
  // The lowering stops at the first step whose force reaches the target; one step moves the lid
  // by speed * dt = 5e-3 x ~1e-5 s = 5e-8 m, 1e-3 of the ~5e-5 m it travels from first touch to
  // the target, so the step's overshoot is far below the 2 % allowed here (which also admits
  // the damping part of the force, ~ c v of the contacts under the moving lid).
  EXPECT_GE(r.lid.stop_force, target);
  EXPECT_LE(r.lid.stop_force, 1.02 * target);
  EXPECT_GE(r.lid.max_force, r.lid.stop_force);
  EXPECT_LT(r.lid.stop_z, r.lid.start_z);
  // Held at the pressure: the servo follows the bed as it creeps into its pores. A proportional
  // servo of gain 10 leaves a steady error of the creep rate over the gain (6 % on the [KE]
  // beds); 10 % bounds the mean force over the second half of the hold.
  EXPECT_NEAR(r.lid.hold_late_force, target, 0.1 * target);
  EXPECT_LE(r.lid.hold_end_z, r.lid.stop_z + 1e-3 * kRadius);  // it follows, never backs off far
  EXPECT_TRUE(r.at_rest);
  // No particle escapes the box, none is above where the lid started.
  EXPECT_EQ(r.lost, 0u);
  for (std::size_t i = 0; i < after.n(); ++i) {
    EXPECT_LE(after.z[i] + after.radius[i], r.lid.start_z + 1e-3 * kRadius) << i;
  }
  // Denser (or as dense) below the lowest level any surface particle reached before: the layer
  // [0, h] with h the lowest particle top of the top 20 % before the lid.
  std::vector<double> tops;
  for (std::size_t i = 0; i < before.n(); ++i) tops.push_back(before.z[i] + before.radius[i]);
  std::sort(tops.begin(), tops.end());
  const double h = tops[tops.size() * 8 / 10] - 2 * kRadius;
  const double rho_before = bed::layer_density(before, 0, h);
  const double rho_after = bed::layer_density(after, 0, h);
  EXPECT_GE(rho_after, rho_before);
  EXPECT_GT(rho_before, 0.4);  // a settled bed, not a gas
}

TEST(Lid, TravelLimitStopsItExactly) {
  const dem::Scene scene = lid_scene();
  bed::Bed b = drop_bed();
  dem::RunSettings s = settle_settings();
  s.lid.enabled = true;
  s.lid.travel = 0.1 * kRadius;
  s.lid.speed = 5e-3;
  s.lid.relax = 0.05;
  const auto r = dem::run_deposition(b, scene, s);
  EXPECT_EQ(r.lid.stopped_by, "travel");
  // The last lowering step clamps the lid at start - travel: exact up to the rounding of the
  // subtraction at the lid's height (~4e-3 m, ulp ~1e-18 m).
  EXPECT_NEAR(r.lid.start_z - r.lid.stop_z, 0.1 * kRadius, 1e-17);
  EXPECT_EQ(r.lost, 0u);
}

TEST(Lid, KeptLidBecomesTheBedsTopFace) {
  const dem::Scene scene = lid_scene();
  bed::Bed b = drop_bed();
  dem::RunSettings s = settle_settings();
  s.lid.enabled = true;
  s.lid.pressure = 2e3;  // Pa
  s.lid.speed = 5e-3;
  s.lid.hold = 0.01;
  s.lid.release = false;
  const auto r = dem::run_deposition(b, scene, s);
  ASSERT_EQ(r.lid.stopped_by, "force");
  // The written bed ends at the lid, and the bed presses on it: centres below, some spheres
  // overlapping it (the hold ends with a force on the lid).
  EXPECT_EQ(b.domain.upper[2], r.lid.hold_end_z);
  std::size_t touching = 0;
  for (std::size_t i = 0; i < b.n(); ++i) {
    EXPECT_LT(b.z[i], b.domain.upper[2]) << i;
    if (b.z[i] + b.radius[i] > b.domain.upper[2]) ++touching;
  }
  EXPECT_GT(touching, 0u);
  EXPECT_GT(r.lid.hold_end_force, 0.0);
  EXPECT_EQ(r.lost, 0u);
}

TEST(Lid, BadSettingsAreRefused) {
  dem::Scene scene = lid_scene();
  bed::Bed b = drop_bed();
  dem::RunSettings s = settle_settings();
  s.lid.enabled = true;
  EXPECT_THROW(dem::run_deposition(b, scene, s), InputError);  // neither pressure nor travel
  s.lid.pressure = 1e3;
  s.lid.speed = 0;
  EXPECT_THROW(dem::run_deposition(b, scene, s), InputError);
  s.lid.speed = 1e-3;
  scene.effects &= ~dem::kWalls;
  EXPECT_THROW(dem::run_deposition(b, scene, s), InputError);  // the lid is a wall
}

TEST(CoreDensity, SimpleCubicLatticeGivesPiOverSix) {
  // Touching spheres (d = 1 mm) on a simple cubic lattice filling a 10 mm cube, shifted off the
  // counting grid. The core (2 mm margins; surface = 90th percentile of the tops, 9 mm) spans
  // whole lattice periods, so its exact density is pi/6.
  const double d = 1e-3;
  bed::Bed b = test::box_bed(10 * d, 10 * d, 10 * d);
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      for (int k = 0; k < 10; ++k) {
        b.add((i + 0.5) * d + 0.1234 * d, (j + 0.5) * d + 0.0567 * d, (k + 0.5) * d, 0.5 * d);
      }
    }
  }
  const dem::CoreDensity core = dem::core_density(b, 2 * d);
  EXPECT_NEAR(core.upper[2], 7 * d, 1e-12);
  // 180 spheres of 10 grid cells in radius: the counting error is ~1e-4 (measured 3e-5 here);
  // 1e-3 keeps it far below the 0.01 porosity differences the beds are judged by.
  EXPECT_NEAR(core.density, std::numbers::pi / 6, 1e-3);
  // A bed thinner than two margins has no core.
  EXPECT_TRUE(std::isnan(dem::core_density(b, 6 * d).density));
}
