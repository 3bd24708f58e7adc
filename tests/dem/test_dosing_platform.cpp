// The dosing platform of a spread (SpreadSettings::platform_edge, dem/src/dosing_platform.hpp):
// the supply lies on it and the tool carries it off, nothing stays under its top, its rise at a
// layer's start removes what it reaches and only that, every particle is accounted for, a
// continued run equals the uninterrupted one, and a platform off the supply or past the tool's
// end is refused.
#include <gtest/gtest.h>

#include <cstddef>

#include "small_spread.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/spread.hpp"

namespace {

using namespace powderbed;
using test::granular_scene;
using test::kRadius;
using test::small_spread;
using test::strip;

constexpr double kEdge = 0.45e-3;  // small_spread's supply ends at 0.4 mm

// small_spread from the platform, the blade at 0.05 m/s: the powder it pushes over the edge
// falls the gap (60 um) in sqrt(2 gap / g) = 3.5 ms, in which the blade goes 0.17 mm, a sixth of
// the strip (at small_spread's 0.2 m/s the small heap flies to the strip's end before it lands).
dem::SpreadSettings on_platform(std::uint64_t layers) {
  dem::SpreadSettings st = small_spread();
  st.tool.speed = 0.05;
  st.platform_edge = kEdge;
  st.layers = layers;
  return st;
}

// Particles on the platform below its top (the tool's bottom): those whose centre lies over it,
// a radius short of its edge, lower than a radius above the top, less 1 % of the radius for the
// softened contact's overlap under the powder's weight.
std::size_t under_the_top(const bed::Bed& b, double top) {
  std::size_t under = 0;
  for (std::size_t i = 0; i < b.n(); ++i)
    under += b.x[i] < kEdge - b.radius[i] && b.z[i] < top + 0.99 * b.radius[i] ? 1 : 0;
  return under;
}

TEST(DosingPlatform, SupplyRestsOnItAndTheToolCarriesItOff) {
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  bed::Bed b = strip();
  std::size_t before = 0;
  const dem::SpreadSettings st = on_platform(2);
  dem::SpreadSettings watched = st;
  watched.layer_done = [&](const dem::LayerSummary& l, const bed::Bed& bed, const dem::SpreadState& state) {
    EXPECT_EQ(under_the_top(bed, l.tool_bottom), 0u) << "layer " << l.layer;
    EXPECT_TRUE(state.floor.empty());  // the part's floor stays the plate's: the platform is not the part
  };
  const dem::SpreadSummary r = dem::run_spread(b, s, watched);
  ASSERT_EQ(r.layers.size(), 2u);
  for (const dem::LayerSummary& l : r.layers) {
    EXPECT_GT(l.supplied, 100u);
    EXPECT_EQ(l.lost, 0u);
    // Every particle is in the bed or counted: supplied, overflow, removed under the platform.
    EXPECT_EQ(l.n, before + l.supplied - l.overflow - l.under_platform) << "layer " << l.layer;
    before = l.n;
    // The blade carried the supply off the platform into a layer behind it.
    EXPECT_GT(l.density_under_gap, 0.05) << "layer " << l.layer;
  }
  EXPECT_EQ(b.n(), before);
}

TEST(DosingPlatform, RiseRemovesWhatItReachesAndOnlyThat) {
  // No supply: one sphere on the plate over the platform's stretch, one in the build's; the
  // platform rises to the tool's bottom (60 um) through the first, the blade passes over both.
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  dem::SpreadSettings st = on_platform(1);
  st.supply = nullptr;
  st.remove_overflow = false;
  bed::Bed b = strip();
  b.add(0.3e-3, 0.15e-3, kRadius, kRadius);
  b.add(0.8e-3, 0.15e-3, kRadius, kRadius);
  const dem::SpreadSummary r = dem::run_spread(b, s, st);
  EXPECT_EQ(r.layers[0].under_platform, 1u);
  ASSERT_EQ(b.n(), 1u);
  EXPECT_EQ(b.id[0], 1u);
  EXPECT_NEAR(b.x[0], 0.8e-3, 1e-3 * kRadius);
}

TEST(DosingPlatform, BedSpreadWithoutItLosesThePowderUnderItsTopAndKeepsTheRest) {
  // A layer spread without the platform leaves powder in the supply region under the gap; a
  // second layer continued on the platform removes it at its start, with its contacts, and the
  // run goes on with every other particle and contact as the state had them.
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  dem::SpreadSettings plain = small_spread();
  bed::Bed b = strip();
  const dem::SpreadSummary first = dem::run_spread(b, s, plain);
  const double top = plain.tool.gap + plain.layer_thickness;  // the table's top in layer 2
  std::size_t reached = 0;
  for (std::size_t i = 0; i < b.n(); ++i) reached += b.x[i] < kEdge - b.radius[i] ? 1 : 0;
  ASSERT_GT(reached, 10u);  // the powder the first layer left under the supply region
  const std::size_t before = b.n();
  dem::SpreadSettings st = on_platform(1);
  st.tool.speed = 0.2;
  dem::LayerSummary second;
  st.layer_done = [&](const dem::LayerSummary& l, const bed::Bed& bed, const dem::SpreadState&) {
    second = l;
    EXPECT_EQ(under_the_top(bed, top), 0u);
  };
  const dem::SpreadSummary rest = dem::run_spread(b, s, st, &first.state);
  EXPECT_GE(second.under_platform, reached);
  EXPECT_EQ(second.n, before + second.supplied - second.overflow - second.under_platform);
  EXPECT_EQ(rest.state.wx.size(), b.n());
  EXPECT_EQ(rest.state.wall_history.size(), b.n() * dem::kWallHistoryValues);
}

TEST(DosingPlatform, ContinuedRunEqualsTheUninterruptedOne) {
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  const auto fast = [](std::uint64_t layers) {  // small_spread's speed: a quarter of the steps
    dem::SpreadSettings st = on_platform(layers);
    st.tool.speed = 0.2;
    return st;
  };
  bed::Bed whole = strip();
  const dem::SpreadSummary straight = dem::run_spread(whole, s, fast(2));
  bed::Bed part = strip();
  const dem::SpreadSummary first = dem::run_spread(part, s, fast(1));
  const dem::SpreadSummary rest = dem::run_spread(part, s, fast(1), &first.state);
  ASSERT_EQ(part.n(), whole.n());
  EXPECT_EQ(test::particles_differing(part, rest, whole, straight), 0u);
  EXPECT_EQ(rest.layers[0].under_platform, straight.layers[1].under_platform);
  EXPECT_EQ(rest.state.pair_history, straight.state.pair_history);
}

TEST(DosingPlatform, PlatformOffTheSupplyOrPastTheToolsEndIsRefused) {
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  for (const double edge : {0.3e-3, 1.2e-3, 1.3e-3}) {  // under the supply; at and past the end
    dem::SpreadSettings st = on_platform(1);
    st.platform_edge = edge;
    bed::Bed b = strip();
    EXPECT_THROW(dem::run_spread(b, s, st), InputError) << edge;
  }
}

}  // namespace
