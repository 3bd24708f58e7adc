// [KE]'s insertion from the top boundary (solver.hpp InsertionSettings) and its consolidation by a
// lid lowered to a depth below the bed's surface, raised and relaxed (LidSettings::depth), on a
// small box with the linear law of their MFiX beds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "beds.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/solver.hpp"

using namespace powderbed;

namespace {

constexpr double kRadius = 0.5e-3;  // m, steel 1 mm as [KE]
constexpr double kSide = 4e-3;      // a cube of 4 diameters

// A pool of 150 spheres parked at the centre (more than a 4 D cube holds: ~0.6 x 64 / 0.52 = 73).
bed::Bed pool(std::size_t count = 150) {
  bed::Bed b = test::box_bed(kSide, kSide, kSide);
  for (std::size_t i = 0; i < count; ++i) b.add(kSide / 2, kSide / 2, kSide / 2, kRadius);
  return b;
}

dem::Scene scene() {
  dem::Scene s;  // every effect on
  s.law = dem::ContactLaw::linear;
  s.stiffness = 1e5;
  s.material.density = 7700;
  s.material.friction = 0.3;
  s.material.damping = 0.3;
  return s;
}

dem::RunSettings settings() {
  dem::RunSettings s;
  s.insertion.enabled = true;
  s.insertion.rate = 5000;
  s.insertion.speed = 0.5;
  s.insertion.seed = 3;
  s.t_end = 0.3;  // insertion ends near 0.03 s; the rest settles
  return s;
}

// Smallest gap between two particles, over the radius (negative: overlap).
double min_gap(const bed::Bed& b) {
  double gap = INFINITY;
  for (std::size_t i = 0; i < b.n(); ++i)
    for (std::size_t j = i + 1; j < b.n(); ++j)
      gap = std::min(gap, (std::hypot(b.x[i] - b.x[j], b.y[i] - b.y[j], b.z[i] - b.z[j]) -
                           b.radius[i] - b.radius[j]) / kRadius);
  return gap;
}

}  // namespace

TEST(Insertion, FillsTheBoxFromTheTopAndDropsTheRestOfThePool) {
  bed::Bed b = pool();
  const auto r = dem::run_deposition(b, scene(), settings());
  EXPECT_EQ(r.insertion_stopped_by, "full");
  EXPECT_EQ(b.n(), r.inserted);
  EXPECT_EQ(r.n, r.inserted);
  // A random loose packing of a 4 D cube with its walls holds 50-80 spheres (solid fraction
  // 0.4-0.63 of the box); the pool's 150 cannot all go in.
  EXPECT_GT(r.inserted, 50u);
  EXPECT_LT(r.inserted, 90u);
  EXPECT_EQ(r.lost, 0u);
  // Settled under gravity with k_n = 1e5 N/m: overlaps ~ the weight of a column over k_n
  // (4 x 4e-5 N / 1e5 = 1.6e-9 m = 3e-6 r); 1e-4 r bounds it and catches spheres inserted into
  // each other (an overlap of order r).
  EXPECT_GT(min_gap(b), -1e-4);
  for (std::size_t i = 0; i < b.n(); ++i) EXPECT_LE(b.z[i] + b.radius[i], kSide + 1e-4 * kRadius);
  // Same seed, same bed.
  bed::Bed again = pool();
  dem::run_deposition(again, scene(), settings());
  EXPECT_EQ(again.x, b.x);
  EXPECT_EQ(again.z, b.z);
}

TEST(Insertion, StopsWhenThePoolIsInOrTheTimeIsUp) {
  bed::Bed small = pool(10);
  auto r = dem::run_deposition(small, scene(), settings());
  EXPECT_EQ(r.insertion_stopped_by, "pool");
  EXPECT_EQ(small.n(), 10u);
  // 5000 /s for 2 ms: the first at t = 0, then one every 0.2 ms before the last step (which
  // starts just short of 2 ms), 10 in.
  bed::Bed b = pool();
  dem::RunSettings s = settings();
  s.t_end = 2e-3;
  r = dem::run_deposition(b, scene(), s);
  EXPECT_EQ(r.insertion_stopped_by, "time");
  EXPECT_EQ(b.n(), 10u);
}

TEST(Insertion, LidToADepthBelowTheSurfaceRaisedAndRelaxed) {
  bed::Bed b = pool();
  dem::run_deposition(b, scene(), settings());
  dem::RunSettings s;
  s.t_end = 1e-4;
  s.lid.enabled = true;
  s.lid.depth = 0.5 * kRadius;
  s.lid.speed = 0.02;
  s.lid.hold = 0.02;
  s.lid.relax = 0.2;
  const auto r = dem::run_deposition(b, scene(), s);
  ASSERT_TRUE(r.lid_used);
  EXPECT_EQ(r.lid.stopped_by, "depth");
  // Stopped at the depth below the 90th-percentile top, to the lowering step (speed x dt).
  EXPECT_NEAR(r.lid.stop_z, r.lid.surface_z - 0.5 * kRadius, 0.02 * r.dt + 1e-12);
  EXPECT_GT(r.lid.max_force, 0);  // it pressed the top layer
  EXPECT_DOUBLE_EQ(b.domain.upper[2], kSide);  // raised again: the box is the box
  EXPECT_EQ(r.lost, 0u);
}

TEST(Insertion, BadSettingsAreRefused) {
  const auto refused = [](auto change) {
    bed::Bed b = pool();
    dem::RunSettings s = settings();
    change(s);
    EXPECT_THROW(dem::run_deposition(b, scene(), s), InputError);
  };
  refused([](dem::RunSettings& s) { s.insertion.rate = 0; });
  refused([](dem::RunSettings& s) { s.insertion.speed = -1; });
  refused([](dem::RunSettings& s) { s.insertion.tries = 0; });
  refused([](dem::RunSettings& s) { s.insertion.patience = -1; });
  refused([](dem::RunSettings& s) {
    s.trajectory = "never-written.h5";
    s.trajectory_every = 10;
  });
  refused([](dem::RunSettings& s) {
    s.lid.enabled = true;
    s.lid.depth = 1e-4;
    s.lid.travel = 1e-4;
  });
}
