// Fusion as bonding (issue 32, point 2): a particle that melted joins the solid only where its
// melt met molten solid, directly or through molten neighbours in contact; one that melted on
// solid that never melted froze as a ball and stays in the bed. Set up by temperatures set on the
// particles and the top face (the peaks fusion reads follow them), so each case is exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "powderbed/thermal/fusion.hpp"
#include "powderbed/thermal/solver.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;

namespace {

constexpr double kR = 15e-6;   // particle radius, m
constexpr double kDx = 5e-6;   // grid spacing, m
constexpr double kHot = 2000;  // K: above 316L's melting point (1700 K) and its window

// A row of `n` particles along x at centre distances 1.98 r (neighbours overlap: one contact
// each), resting on a 200 x 120 um plate, the row's middle at the plate's centre.
bed::Bed row(std::size_t n) {
  bed::Bed b = test::empty_bed(200e-6, 120e-6, 60e-6);
  const double x0 = 100e-6 - 0.5 * static_cast<double>(n - 1) * 1.98 * kR;
  for (std::size_t i = 0; i < n; ++i)
    b.add(x0 + static_cast<double>(i) * 1.98 * kR, 60e-6, test::resting_z(kR), kR);
  return b;
}

thermal::SinterScene scene() {
  return test::small_scene(thermal::kAllSinterEffects, {41, 25, 7}, 30e-6);
}

// Melts the top face within `reach` of (x, y): the solid under a particle remelted.
void melt_top_under(thermal::Sinter& s, double x, double y, double reach) {
  const auto& g = s.grid();
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      if (std::hypot(g.x(i) - x, g.y(j) - y) <= reach) s.set_substrate_temperature(g.index(i, j, g.k_plate()), kHot);
}

bool top_is_flat(const thermal::Fusion& f, double z_top) {
  return std::all_of(f.top.begin(), f.top.end(), [&](double h) { return h == z_top; });
}

}  // namespace

// A droplet on cold solid: melted, met no molten solid, stays in the bed as a ball; the solid is
// untouched and the mass is all still in the bed.
TEST(Bonding, MoltenParticleOnColdSolidBalls) {
  const bed::Bed b = row(1);
  thermal::Sinter s(b, scene(), test::table_316l());
  s.set_particle_temperature(0, kHot);
  const thermal::Fusion f = thermal::fuse(b, s);
  EXPECT_EQ(f.fused, 0u);
  EXPECT_EQ(f.balled, 1u);
  ASSERT_EQ(f.state.size(), 1u);
  EXPECT_EQ(f.state[0], thermal::kBalled);
  EXPECT_EQ(f.powder.n(), 1u) << "a ball stays in the bed";
  EXPECT_TRUE(top_is_flat(f, s.grid().z_top));
  EXPECT_DOUBLE_EQ(f.powder_mass_after, f.powder_mass_before);
  EXPECT_LT(f.mass_error(), 1e-12);
}

// The same droplet on solid that remelted under it bonds: it leaves the bed and raises the top.
TEST(Bonding, MoltenParticleOnRemeltedSolidFuses) {
  const bed::Bed b = row(1);
  thermal::Sinter s(b, scene(), test::table_316l());
  s.set_particle_temperature(0, kHot);
  melt_top_under(s, b.x[0], b.y[0], kDx);
  const thermal::Fusion f = thermal::fuse(b, s);
  EXPECT_EQ(f.fused, 1u);
  EXPECT_EQ(f.balled, 0u);
  EXPECT_EQ(f.powder.n(), 0u);
  EXPECT_FALSE(top_is_flat(f, s.grid().z_top));
  EXPECT_LT(f.mass_error(), 1e-12);
}

// The bond runs through molten neighbours in contact: with the solid remelted under the first
// of three only, all three fuse; with the middle one never molten, the third is cut off and
// balls while the middle one stays powder.
TEST(Bonding, BondRunsThroughMoltenNeighboursOnly) {
  const bed::Bed b = row(3);
  {
    thermal::Sinter s(b, scene(), test::table_316l());
    for (std::size_t i = 0; i < 3; ++i) s.set_particle_temperature(i, kHot);
    melt_top_under(s, b.x[0], b.y[0], kDx);
    const thermal::Fusion f = thermal::fuse(b, s);
    EXPECT_EQ(f.fused, 3u);
    EXPECT_EQ(f.balled, 0u);
  }
  thermal::Sinter s(b, scene(), test::table_316l());
  s.set_particle_temperature(0, kHot);
  s.set_particle_temperature(2, kHot);
  melt_top_under(s, b.x[0], b.y[0], kDx);
  const thermal::Fusion f = thermal::fuse(b, s);
  EXPECT_EQ(f.state[0], thermal::kFused);
  EXPECT_EQ(f.state[1], thermal::kPowder);
  EXPECT_EQ(f.state[2], thermal::kBalled);
  EXPECT_EQ(f.fused, 1u);
  EXPECT_EQ(f.balled, 1u);
  EXPECT_EQ(f.powder.n(), 2u);
  EXPECT_LT(f.mass_error(), 1e-12);
}

// Resting is judged as finely as the grid knows the solid's top (dz/2, here 2.5 um): a molten
// particle 1 um above remelted solid (a spread layer's particles settle that loosely) bonds; one
// 10 um above it, held there by nothing molten, balls.
TEST(Bonding, RestingIsJudgedToHalfACell) {
  for (const auto& [gap, expected] : {std::pair{1e-6, thermal::kFused}, std::pair{10e-6, thermal::kBalled}}) {
    bed::Bed b = row(1);
    b.z[0] = kR + gap;
    b.add(30e-6, 30e-6, test::resting_z(kR), kR);  // cold, resting: the solver's floor check
    thermal::Sinter s(b, scene(), test::table_316l());
    ASSERT_NEAR(s.grid().dz, 5e-6, 1e-12);
    s.set_particle_temperature(0, kHot);
    melt_top_under(s, b.x[0], b.y[0], kDx);
    EXPECT_EQ(thermal::fuse(b, s).state[0], expected) << "gap " << gap;
  }
}

// The fused fraction counts what joined the solid only (issue 36: a layer was reported 100 %
// fused when 156 of 159 particles vaporised): of three equal particles, one vaporised (above the
// boiling point, no evaporation model) and two bonded, two thirds fused; all three vaporised,
// none. Mass is conserved either way.
TEST(Bonding, FusedFractionCountsNoVapour) {
  const bed::Bed b = row(3);
  for (const std::size_t vaporised : {1u, 3u}) {
    thermal::Sinter s(b, scene(), test::table_316l());
    for (std::size_t i = 0; i < 3; ++i) s.set_particle_temperature(i, i < vaporised ? 4000 : kHot);
    for (std::size_t i = 0; i < 3; ++i) melt_top_under(s, b.x[i], b.y[i], kDx);
    const thermal::Fusion f = thermal::fuse(b, s);
    EXPECT_EQ(f.vaporised, vaporised);
    EXPECT_EQ(f.fused, 3 - vaporised);
    EXPECT_NEAR(f.fused_fraction(), (3.0 - static_cast<double>(vaporised)) / 3.0, 1e-12);
    EXPECT_LT(f.mass_error(), 1e-12);
  }
}
