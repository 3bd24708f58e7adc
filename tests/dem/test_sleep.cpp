// Sleeping powder (SpreadSettings::sleep, dem/src/sleep.hpp) on the small blade spread: sleepers
// never move and lie under the tool's reach, the layer is the one a run without sleep leaves
// within the seed-to-seed spread, a continued run and any thread count give the same bits, and
// bad settings are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/spread.hpp"
#include "small_spread.hpp"

namespace {

using namespace powderbed;
using test::granular_scene;
using test::small_spread;
using test::strip;

// The recoater tests' scene with a damping ratio of 0.5 (theirs: 0.1), so that this small bed of
// equal spheres comes to rest within the layers' settling.
dem::Scene scene() {
  dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  s.material.damping = 0.5;
  return s;
}

dem::SpreadSettings sleeping_spread(std::uint64_t layers) {
  dem::SpreadSettings st = small_spread();
  st.layers = layers;
  st.chamber = true;
  st.sleep.on = true;
  // The supply and the layer settle for 2 ms each (small_spread: none), so that the bed under a
  // layer is at rest when the next begins.
  st.tool.delay = 2e-3;
  st.tool.settle = 2e-3;
  return st;
}

TEST(Sleep, SleepersStayPutUnderTheToolsReach) {
  // A sleeper is not integrated: its velocity is exactly 0 (an awake particle's never is, under
  // gravity). Step by step, every particle at rest must lie wholly under the tool's bottom, and
  // one at rest on two steps in a row must not have moved.
  const dem::Scene s = scene();
  dem::SpreadSettings st = sleeping_spread(3);
  std::map<std::uint64_t, std::array<double, 3>> resting;  // by id, at the last step
  std::size_t checked = 0, moved = 0, in_reach = 0;
  double bottom = 0;
  st.observer = [&](std::uint64_t, double, const bed::Bed& b, const std::vector<double>&) {
    std::map<std::uint64_t, std::array<double, 3>> now;
    for (std::size_t i = 0; i < b.n(); ++i) {
      if (b.vx[i] != 0 || b.vy[i] != 0 || b.vz[i] != 0) continue;
      now[b.id[i]] = {b.x[i], b.y[i], b.z[i]};
      in_reach += b.z[i] + b.radius[i] >= bottom ? 1 : 0;
      const auto it = resting.find(b.id[i]);
      if (it == resting.end()) continue;
      ++checked;
      moved += it->second != now[b.id[i]] ? 1 : 0;
    }
    resting = std::move(now);
    return false;
  };
  st.layer_done = [&](const dem::LayerSummary& l, const bed::Bed&, const dem::SpreadState&) {
    bottom = st.tool.gap + static_cast<double>(l.layer) * st.layer_thickness;  // the next layer's
    resting.clear();
  };
  bottom = st.tool.gap;
  bed::Bed b = strip();
  const dem::SpreadSummary r = dem::run_spread(b, s, st);
  ASSERT_EQ(r.layers.size(), 3u);
  EXPECT_GT(r.layers[2].asleep, 10.0);  // something slept
  EXPECT_GT(checked, 1000u);
  EXPECT_EQ(moved, 0u);
  EXPECT_EQ(in_reach, 0u);
  for (const dem::LayerSummary& l : r.layers) EXPECT_EQ(l.lost, 0u) << "layer " << l.layer;
}

// The density under the gap after three layers on the jittered supply of `seed`, sleeping or
// not.
double density(std::uint64_t seed, bool sleep) {
  dem::SpreadSettings st = sleeping_spread(3);
  st.sleep.on = sleep;
  st.supply = test::jittered_supply(seed);
  bed::Bed b = strip();
  return dem::run_spread(b, scene(), st).layers.back().density_under_gap;
}

TEST(Sleep, LeavesTheLayerDensityWithinTheSeedSpread) {
  // As FrozenPowderLeavesTheLayerDensityWithinTheSeedSpread (test_spread.cpp): over three seeds
  // the mean density with sleep must differ from the mean without by no more than the runs
  // without differ among themselves.
  double lo = 1, hi = 0, mean_awake = 0, mean_sleeping = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const double awake = density(seed, false);
    lo = std::min(lo, awake);
    hi = std::max(hi, awake);
    mean_awake += awake / 3.0;
    mean_sleeping += density(seed, true) / 3.0;
  }
  EXPECT_GT(hi - lo, 0.0);
  EXPECT_LE(std::abs(mean_sleeping - mean_awake), hi - lo) << mean_sleeping << " against " << mean_awake;
}

TEST(Sleep, ContinuedRunEqualsTheUninterruptedOneOnAnyThreads) {
  // Every particle wakes at a layer's start, and the dormant contacts are in the state a
  // restart carries, so layer 3 continued from layer 2's state is the uninterrupted layer 3;
  // and the sets change from per-particle tests, so two threads give the same bits.
  const dem::Scene s = scene();
  bed::Bed whole = strip();
  const dem::SpreadSummary straight = dem::run_spread(whole, s, sleeping_spread(3));
  ASSERT_GT(straight.layers[1].asleep, 0.0);
  bed::Bed part = strip();
  const dem::SpreadSummary first = dem::run_spread(part, s, sleeping_spread(2));
  dem::SpreadSettings one = sleeping_spread(1);
  one.threads = 2;
  one.parallel_min_particles = 0;
  const dem::SpreadSummary rest = dem::run_spread(part, s, one, &first.state);
  ASSERT_EQ(part.n(), whole.n());
  EXPECT_EQ(test::particles_differing(part, rest, whole, straight), 0u);
  EXPECT_EQ(rest.state.pair_history, straight.state.pair_history);
  EXPECT_EQ(rest.layers[0].sleep_changes, straight.layers[2].sleep_changes);
}

TEST(Sleep, BadSettingsAreRefused) {
  const dem::Scene s = scene();
  const auto refused = [&](auto change) {
    dem::SpreadSettings st = sleeping_spread(1);
    change(st);
    bed::Bed b = strip();
    EXPECT_THROW(dem::run_spread(b, s, st), InputError);
  };
  refused([](dem::SpreadSettings& st) { st.sleep.speed = 0; });
  refused([](dem::SpreadSettings& st) { st.sleep.wake_speed = st.sleep.speed; });
  refused([](dem::SpreadSettings& st) { st.sleep.steps = 0; });
  refused([](dem::SpreadSettings& st) { st.freeze_depth = 60e-6; });
}

}  // namespace
