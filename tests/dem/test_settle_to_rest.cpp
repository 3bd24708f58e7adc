// A spread layer settling to rest (SpreadSettings::until_rest): the small blade spread of
// small_spread.hpp stops its tool with the last powder it let fall still moving; settled to
// rest, no particle behind the tool moves faster than the rest speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/rest_criteria.hpp"
#include "small_spread.hpp"

namespace powderbed {
namespace {

using test::granular_scene;
using test::small_spread;
using test::strip;

// The fastest speed of the particles whose centres lie behind x.
double fastest_behind(const bed::Bed& b, double x) {
  double v = 0;
  for (std::size_t i = 0; i < b.n(); ++i)
    if (b.x[i] < x) v = std::max(v, std::hypot(b.vx[i], b.vy[i], b.vz[i]));
  return v;
}

dem::SpreadSettings settling(double speed, double window, double cap) {
  dem::SpreadSettings st = small_spread();
  st.until_rest = true;
  st.rest.max_speed = speed;
  st.rest.window = window;
  st.rest_cap = cap;
  return st;
}

// The one rest test of the drop and the spread: a window of 1 ms at dt = 1e-5 s is 100 steps,
// checked every 10; it counts from the first quiet check, and a loud check starts it again.
TEST(RestWatch, RestAfterAWindowOfQuietChecksCountedFromTheFirst) {
  dem::RestCriteria rest;
  rest.window = 1e-3;
  dem::RestWatch watch(rest, 1e-5);
  ASSERT_EQ(watch.every(), 10u);
  EXPECT_FALSE(watch.check(0, false));
  EXPECT_FALSE(watch.check(10, true));  // the stretch starts here
  EXPECT_FALSE(watch.check(100, true));  // 90 steps quiet: short of the window
  EXPECT_TRUE(watch.check(110, true));
  EXPECT_FALSE(watch.check(120, false));  // loud: the stretch ends
  EXPECT_FALSE(watch.check(130, true));
  EXPECT_FALSE(watch.check(220, true));
  EXPECT_TRUE(watch.check(230, true));
  watch.reset();
  EXPECT_FALSE(watch.check(240, true));
}

// A window of zero: rest at the first quiet check; checks never come every step of a long window.
TEST(RestWatch, ZeroWindowRestsAtOnceAndLongWindowsCheckEveryHundredSteps) {
  dem::RestCriteria rest;
  rest.window = 0;
  dem::RestWatch now(rest, 1e-5);
  EXPECT_EQ(now.every(), 1u);
  EXPECT_TRUE(now.check(0, true));
  rest.window = 1.0;
  EXPECT_EQ(dem::RestWatch(rest, 1e-5).every(), 100u);
}

TEST(SettleToRest, LayerSettlesUntilThePowderBehindTheToolRests) {
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  const double back = small_spread().tool.end - 0.5 * small_spread().tool.thickness;
  bed::Bed fixed = strip();
  const dem::SpreadSummary stopped = dem::run_spread(fixed, s, small_spread());
  EXPECT_FALSE(stopped.layers[0].at_rest);
  EXPECT_GT(fastest_behind(fixed, back), 1e-3);  // the tool stopped with powder still falling

  bed::Bed b = strip();
  dem::SpreadSettings st = settling(1e-3, 2e-4, 0.05);
  // Progress plans the pass and the cap: it never goes back, and a layer resting well before
  // the cap ends short of 1.
  std::vector<double> fractions;
  st.progress = [&](double f, double) { fractions.push_back(f); };
  st.progress_every = 100;
  const dem::SpreadSummary r = dem::run_spread(b, s, st);
  const dem::LayerSummary& layer = r.layers[0];
  ASSERT_GT(fractions.size(), 2u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_LT(fractions.back(), 1.0);
  EXPECT_TRUE(layer.at_rest);
  EXPECT_GE(layer.settle_time, 2e-4);  // calm for the window at least
  EXPECT_LT(layer.settle_time, 0.05);
  EXPECT_LT(fastest_behind(b, back), 1e-3);
  EXPECT_GT(layer.steps, stopped.layers[0].steps);
}

TEST(SettleToRest, CapEndsALayerThatDoesNotRestAndSaysSo) {
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  bed::Bed b = strip();
  const double cap = 1e-4;
  const dem::SpreadSummary r = dem::run_spread(b, s, settling(1e-12, 1e-3, cap));
  EXPECT_FALSE(r.layers[0].at_rest);
  // Settled for the cap, in checks of at most 100 steps past it.
  EXPECT_GE(r.layers[0].settle_time, cap);
  EXPECT_LE(r.layers[0].settle_time, cap + 100 * r.dt);
}

TEST(SettleToRest, BadRestSettingsAreRefused) {
  const dem::Scene s = granular_scene(0.5, 0, dem::FrictionModel::history);
  for (const auto& st : {settling(0, 1e-3, 0.1), settling(1e-4, -1, 0.1), settling(1e-4, 1e-3, 0)}) {
    bed::Bed b = strip();
    EXPECT_THROW(dem::run_spread(b, s, st), InputError);
  }
}

}  // namespace
}  // namespace powderbed
