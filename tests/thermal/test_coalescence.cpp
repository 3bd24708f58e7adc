// Coalescence of molten particles (issue 31, point 4; coalescence.cpp): two wholly molten
// particles in contact become one drop with their summed mass and enthalpy, the lower one's
// bottom and the radius of their summed volume; fusion counts the merged particle as its drop
// does. Set up by temperatures set on the particles with the laser off, so each case is exact;
// then a whole pass under the beam, whose balances must still close.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>

#include "powderbed/thermal/fusion.hpp"
#include "powderbed/thermal/solver.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;

namespace {

constexpr double kR = 12.5e-6;  // particle radius, m
constexpr double kHot = 2000;   // K: above 316L's melting window (1690-1710 K)
// Round-off of a sum of two masses, a cube root and a handful of products: ~1e-16 relative;
// 1e-12 still catches any lost share (a drop missing its partner is off by half).
constexpr double kRoundOff = 1e-12;

// The laser off, wetting on: what happens is what the set temperatures start.
thermal::SinterScene dark_scene() {
  auto scene = test::small_scene(thermal::kAllSinterEffects | thermal::kWetting, {21, 13, 7},
                                 40e-6);
  scene.power = 0;
  scene.t_end = 2e-6;
  return scene;
}

double total(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

// With the laser off the ledger's own relative error divides by the small surface losses; the
// gap is measured here against the heat the drops hold instead (at least c (T - T0) per kg with
// c ≥ 450 J/kgK for 316L), which a merge that lost or doubled a share would miss by half.
void expect_balanced(const thermal::EnergyLedger& e, double mass, double t0) {
  const double in = e.absorbed() + e.convection + e.radiation + e.evaporation;
  const double out = e.internal_particles + e.internal_substrate + e.boundary;
  EXPECT_LT(std::abs(in - out), kRoundOff * mass * 450 * (kHot - t0));
}

// Sets the first n particles wholly molten and runs in the dark, the energy balance checked;
// returns the particles' mass before.
double melt_and_run(thermal::Sinter& sinter, std::size_t n, thermal::SinterResult& r) {
  const double mass = total(sinter.particle_mass());
  for (std::size_t i = 0; i < n; ++i) sinter.set_particle_temperature(i, kHot);
  r = sinter.run(nullptr, 0, nullptr);
  expect_balanced(r.energy, mass, sinter.scene().initial_temperature);
  return mass;
}

// One particle resting on the plate and one resting on it, the two overlapping by 1 % of a
// diameter.
bed::Bed stacked_pair() {
  bed::Bed bed = test::empty_bed(120e-6, 72e-6, 80e-6);
  const double z0 = test::resting_z(kR);
  bed.add(60e-6, 36e-6, z0, kR);
  bed.add(60e-6, 36e-6, z0 + 1.98 * kR, kR);
  return bed;
}

}  // namespace

// One particle on the plate, one on top of it, both molten: the upper one runs into the lower,
// which keeps its bottom and grows to the radius of their summed volume.
TEST(Coalescence, TwoStackedDropsBecomeOneOnTheLowersBase) {
  bed::Bed bed = stacked_pair();
  const double z0 = bed.z[0];
  thermal::Sinter sinter(bed, dark_scene(), test::table_316l());
  thermal::SinterResult r;
  const double mass_before = melt_and_run(sinter, 2, r);
  EXPECT_EQ(r.particles_coalesced, 1u);
  ASSERT_EQ(sinter.particle_coalesced_into()[1], 0u);
  EXPECT_EQ(sinter.particle_coalesced_into()[0], 0u);
  EXPECT_NEAR(sinter.particle_mass()[0], mass_before, kRoundOff * mass_before);
  EXPECT_EQ(sinter.particle_mass()[1], 0.0);
  const double grown = std::cbrt(2.0) * kR;
  EXPECT_NEAR(sinter.particle_radius()[0], grown, kRoundOff * kR);
  EXPECT_NEAR(sinter.particle_z()[0] - grown, z0 - kR, kRoundOff * kR);
  // The plate stayed cold (no laser): the drop froze as a ball, and both particles are that
  // ball; the bed keeps it at its grown size, with all the mass.
  const thermal::Fusion f = thermal::fuse(bed, sinter);
  EXPECT_LT(f.mass_error(), kRoundOff);
  EXPECT_EQ(f.state[0], thermal::kBalled);
  EXPECT_EQ(f.state[1], thermal::kBalled);
  EXPECT_EQ(f.balled, 2u);
  ASSERT_EQ(f.powder.n(), 1u);
  EXPECT_NEAR(f.powder.radius[0], grown, kRoundOff * kR);
  EXPECT_NEAR(f.powder_mass_after, mass_before, kRoundOff * mass_before);
}

// A row of three molten particles on the plate, each touching the next: one drop at the first
// (equal bottoms: the first survives), grown to the volume of all three, in one check.
TEST(Coalescence, ARowOfDropsMergesIntoOne) {
  bed::Bed bed = test::empty_bed(160e-6, 72e-6, 60e-6);
  for (std::size_t i = 0; i < 3; ++i)
    bed.add(50e-6 + 1.98 * kR * static_cast<double>(i), 36e-6, test::resting_z(kR), kR);
  thermal::Sinter sinter(bed, dark_scene(), test::table_316l());
  thermal::SinterResult r;
  const double mass_before = melt_and_run(sinter, 3, r);
  EXPECT_EQ(r.particles_coalesced, 2u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(sinter.particle_coalesced_into()[i], 0u) << i;
  EXPECT_NEAR(sinter.particle_mass()[0], mass_before, kRoundOff * mass_before);
  EXPECT_NEAR(sinter.particle_radius()[0], std::cbrt(3.0) * kR, kRoundOff * kR);
}

// A molten particle on a solid one (which rests on the plate; the molten one touches only it):
// nothing merges (only melt meets melt). Their contact takes the neck of the smaller sphere:
// just molten (2000 K against 363 K: the interface sits near 1,400 K, below T_m) behind the
// arrested interface's conductance h_c, a slab k(T_m)/h_c added to the conduction length;
// superheated to 3000 K (interface ≈ 2,000 K) it remelts the neighbour's surface and the bridge
// conducts over the centre distance alone.
TEST(Coalescence, MeltOnSolidNeighbourArrestsUnlessItRemeltsIt) {
  bed::Bed bed = test::empty_bed(120e-6, 72e-6, 80e-6);
  const double d = 1.98 * kR;
  bed.add(50e-6, 36e-6, test::resting_z(kR) + d, kR);
  bed.add(50e-6, 36e-6, test::resting_z(kR), kR);
  for (const double hot : {kHot, 3000.0}) {
    const thermal::SinterScene scene = dark_scene();
    thermal::Sinter sinter(bed, scene, test::table_316l());
    sinter.set_particle_temperature(0, hot);
    const auto r = sinter.run(nullptr, 0, nullptr);
    EXPECT_EQ(r.particles_coalesced, 0u);
    EXPECT_EQ(sinter.particle_radius()[1], kR);
    const double slab =
        hot < 2500 ? sinter.material().conductivity(scene.phase_change.melting_point) /
                         scene.arrested_conductance
                   : 0.0;
    ASSERT_EQ(sinter.network().pairs.size(), 1u);
    EXPECT_NEAR(sinter.network().pairs[0].shape, std::numbers::pi * kR * kR / (d + slab),
                kRoundOff * kR)
        << hot << " K";
    EXPECT_EQ(r.bridges, hot < 2500 ? 0u : 1u);
  }
}

// A superheated particle on the plate remelts it, spreads and merges into the pool; the cold
// particle resting on it then touches the pool: it keeps the contact it had with the merged
// one, now with the pool's top nodes, and heats through it (without that contact it would be
// left touching nothing, at T0).
TEST(Coalescence, WhatTouchedAMergedParticleTouchesThePool) {
  const bed::Bed bed = stacked_pair();
  const thermal::SinterScene scene = dark_scene();
  thermal::Sinter sinter(bed, scene, test::table_316l());
  sinter.set_particle_temperature(0, 3000);
  double at_merge = NAN;  // the cold particle's temperature at the first step after the merge
  const auto r = sinter.run(
      [&](const thermal::Sinter& s) {
        if (std::isnan(at_merge) && s.particle_merged()[0]) at_merge = s.particle_temperature()[1];
      },
      1, nullptr);
  ASSERT_EQ(r.particles_merged, 1u);
  EXPECT_EQ(sinter.particle_merged()[1], 0);
  EXPECT_EQ(sinter.network().pairs[0].shape, 0.0);  // the pair is now a contact with the pool
  const double end = sinter.particle_temperature()[1];
  std::printf("  the particle on the merged one: %.1f K at the merge, %.1f K at the end\n",
              at_merge, end);
  // Heated by the pool ~9 K over the steps after the merge; touching nothing it would lose
  // only what it radiates (well under 0.1 K at ~400 K).
  EXPECT_GT(end, at_merge + 5);
}

// The two-layer lattice under the ray-traced 200 W beam with every effect: particles melt,
// coalesce, merge into the pool and evaporate. Mass is conserved exactly (in the particles, the
// pool's rise and the vapour), the energy ledger closes, and fusion accounts for every
// particle once.
TEST(Coalescence, WholePassConservesMassAndCountsEveryParticle) {
  const bed::Bed bed = test::lattice_bed(7, 4, kR);
  thermal::SinterScene scene;
  scene.speed = 1.0;
  scene.nodes = {37, 21, 21};
  scene.substrate_depth = 150e-6;
  thermal::Sinter sinter(bed, scene, test::table_316l());
  const double mass_before = total(sinter.particle_mass());
  const auto r = sinter.run(nullptr, 0, nullptr);
  std::printf("  %zu molten, %zu coalesced, %zu merged, %zu vaporised\n", r.particles_molten,
              r.particles_coalesced, r.particles_merged, r.particles_vaporised);
  EXPECT_GT(r.particles_coalesced, 0u);
  EXPECT_LT(r.energy.relative_error(), kRoundOff);
  EXPECT_NEAR(total(sinter.particle_mass()) + r.evaporated_mass_particles, mass_before,
              kRoundOff * mass_before);
  const thermal::Fusion f = thermal::fuse(bed, sinter, 0.5);
  EXPECT_LT(f.mass_error(), kRoundOff);
  std::size_t powder = 0;
  for (const auto state : f.state) powder += state == thermal::kPowder ? 1 : 0;
  EXPECT_EQ(f.fused + f.balled + f.vaporised + powder, bed.n());
}
