// Hard cases of issue 5 through the library: no conduction path, no particles, a 1 K window,
// vaporisation at 400 W and 0.4 m/s, tiny particles beside big ones, and a time step beyond
// the explicit bound. Each must stay finite and keep the energy balance.
#include <gtest/gtest.h>

#include <cmath>

#include "powderbed/bed/errors.hpp"
#include "powderbed/thermal/solver.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;

namespace {

// The bar of test_energy_balance.cpp: the ledger closes to round-off (~1e-15 measured).
constexpr double kBalance = 1e-6;

void expect_finite(const thermal::Sinter& s, const thermal::SinterResult& r) {
  for (const double t : s.particle_temperature()) EXPECT_TRUE(std::isfinite(t));
  for (const double t : s.substrate_temperature()) EXPECT_TRUE(std::isfinite(t));
  EXPECT_TRUE(std::isfinite(r.max_temperature));
  EXPECT_TRUE(std::isfinite(r.energy.relative_error()));
}

// [GZ]'s hardest sweep point, 400 W at 0.4 m/s, over a 7 x 4 lattice bed.
thermal::SinterScene vaporising_scene() {
  auto scene = test::small_scene(thermal::kAllSinterEffects, {15, 9, 7}, 60e-6);
  scene.power = 400;
  scene.speed = 0.4;
  return scene;
}

}  // namespace

// Particle 0 rests on the floor alone; particle 1 floats 20 µm above the floor touching
// nothing (the bed still rests on its floor through particle 0). With substrate contact off
// neither has any conduction path; the laser crosses both.
TEST(HardCases, ParticlesWithoutConductionPath) {
  bed::Bed bed = test::empty_bed(180e-6, 100e-6, 80e-6);
  bed.add(50e-6, 50e-6, test::resting_z(15e-6), 15e-6);
  bed.add(130e-6, 50e-6, 30e-6, 10e-6);
  for (const unsigned effects :
       {thermal::kAllSinterEffects & ~thermal::kSubstrateContact, thermal::kAllSinterEffects}) {
    const auto scene = test::small_scene(effects, {19, 11, 7}, 60e-6);
    thermal::Sinter sinter(bed, scene, test::table_316l());
    ASSERT_EQ(sinter.network().isolated.size(), 1u);
    EXPECT_EQ(sinter.network().isolated[0], 1u);
    EXPECT_TRUE(sinter.surface().exposed[0] && sinter.surface().exposed[1]);
    const auto r = sinter.run(nullptr, 0, nullptr);
    expect_finite(sinter, r);
    // Only the laser, convection and radiation reach them: both heat well above T0.
    EXPECT_GT(sinter.particle_max_temperature()[0], 1000);
    EXPECT_GT(sinter.particle_max_temperature()[1], 1000);
    EXPECT_LT(r.energy.relative_error(), kBalance) << "effects " << effects;
  }
}

// A bare substrate under 400 W at 0.5 m/s: all the absorbed power reaches the top face (no
// powder, beta = 0) and melts it on the measuring plane.
TEST(HardCases, BareSubstrate) {
  const bed::Bed bed = test::empty_bed(200e-6, 120e-6, 80e-6);
  auto scene = test::small_scene(thermal::kAllSinterEffects, {21, 13, 9}, 80e-6);
  scene.power = 400;
  scene.speed = 0.5;
  thermal::Sinter sinter(bed, scene, test::table_316l());
  EXPECT_EQ(sinter.extinction(), 0.0);
  const auto r = sinter.run(nullptr, 0, nullptr);
  expect_finite(sinter, r);
  EXPECT_EQ(r.energy.laser_particles, 0.0);
  EXPECT_GT(r.energy.laser_substrate, 0.0);
  EXPECT_LT(r.energy.relative_error(), kBalance);
  EXPECT_GT(r.melt_pool.depth, 0.0);
  EXPECT_GT(r.melt_pool.width, 0.0);
  EXPECT_EQ(r.melt_pool.height, 0.0);  // no particles: nothing above the substrate
}

// A 1 K window: the apparent capacity inside is L_m / 1 K = 3e5 J/kgK, a 600-fold jump at its
// edges. The enthalpy state steps over it without trouble.
TEST(HardCases, OneKelvinWindow) {
  const bed::Bed bed = test::lattice_bed(7, 4, 12.5e-6);
  auto scene = test::small_scene(thermal::kAllSinterEffects, {15, 9, 7}, 60e-6);
  scene.phase_change.window = 1;
  thermal::Sinter sinter(bed, scene, test::table_316l());
  const auto r = sinter.run(nullptr, 0, nullptr);
  expect_finite(sinter, r);
  EXPECT_GT(r.particles_molten, 0u);
  EXPECT_LT(r.energy.relative_error(), kBalance);
}

// [GZ]'s hardest sweep point, 400 W at 0.4 m/s: particles pass T_v and leave the network.
TEST(HardCases, VaporisationAt400WAndSlowScan) {
  const bed::Bed bed = test::lattice_bed(7, 4, 12.5e-6);
  const auto scene = vaporising_scene();
  thermal::Sinter sinter(bed, scene, test::table_316l());
  const auto r = sinter.run(nullptr, 0, nullptr);
  expect_finite(sinter, r);
  EXPECT_GT(r.particles_vaporised, 0u);
  EXPECT_LT(r.energy.relative_error(), kBalance);
  const auto phase = sinter.particle_phase();
  const auto& peak = sinter.particle_max_temperature();
  const auto& pc = scene.phase_change;
  std::size_t gas = 0;
  for (std::size_t i = 0; i < phase.size(); ++i) {
    EXPECT_LE(phase[i], 2u);
    // Past the top of the vaporisation window a particle has left the bed: reported gas.
    if (peak[i] >= pc.boiling_point + 0.5 * pc.window) {
      EXPECT_EQ(phase[i], 2u) << i;
    }
    if (phase[i] == 2) {
      ++gas;
      EXPECT_GE(peak[i], pc.boiling_point) << i;
    }
  }
  EXPECT_GT(gas, 0u);
  EXPECT_LE(gas, r.particles_vaporised);
}

// The same pass with backward Euler: vaporised particles keep their matrix entries at
// conductance 0 (the pattern is reused every step), so the step after the first particle
// leaves must still solve and book correctly.
TEST(HardCases, VaporisationWithTheImplicitIntegrator) {
  const bed::Bed bed = test::lattice_bed(7, 4, 12.5e-6);
  auto scene = vaporising_scene();
  scene.integrator = thermal::Integrator::implicit_euler;
  thermal::Sinter sinter(bed, scene, test::table_316l());
  const auto r = sinter.run(nullptr, 0, nullptr);
  expect_finite(sinter, r);
  EXPECT_GT(r.particles_vaporised, 0u);
  EXPECT_LT(r.energy.relative_error(), kBalance);
}

// Bimodal (sinter_beds.hpp): tiny r = 2 µm spheres beside and on top of r = 20 µm ones,
// overlapping them by 20 % of their radius.
TEST(HardCases, TinyParticlesBesideBigOnes) {
  const bed::Bed bed = test::bimodal_bed(0.2);
  thermal::Sinter sinter(bed, test::small_scene(thermal::kAllSinterEffects, {15, 9, 7}, 60e-6),
                         test::table_316l());
  EXPECT_EQ(sinter.network().isolated.size(), 0u);
  const auto r = sinter.run(nullptr, 0, nullptr);
  expect_finite(sinter, r);
  EXPECT_LT(r.energy.relative_error(), kBalance);
  // The tiny ones on top take the full beam on a 1/10 radius: they heat ten times faster than
  // the big ones (absorbed power ~ r^2, capacity ~ r^3).
  double tiny_top = 0, big_peak = 0;
  for (std::size_t p = 0; p < bed.n(); p += 3) {
    big_peak = std::max(big_peak, sinter.particle_max_temperature()[p]);
    tiny_top = std::max(tiny_top, sinter.particle_max_temperature()[p + 2]);
  }
  EXPECT_GT(tiny_top, big_peak);
}

// A user dt above the grid's forward-Euler bound is refused; with unsafe_dt it runs and the
// blow-up is caught as a NumericalError naming the step, not returned as numbers.
TEST(HardCases, TimeStepBeyondTheBound) {
  const bed::Bed bed = test::lattice_bed(4, 3, 12.5e-6);
  auto scene = test::small_scene(thermal::kAllSinterEffects, {11, 7, 7}, 60e-6);
  double bound = 0;
  {
    thermal::Sinter probe(bed, scene, test::table_316l());
    bound = probe.stable_steps().grid;
  }
  scene.dt = 3 * bound;
  EXPECT_THROW(thermal::Sinter(bed, scene, test::table_316l()), InputError);
  scene.unsafe_dt = true;
  // The checkerboard mode grows by |1 - lambda dt| >= 3 a step (the bound is conservative by
  // ~1.5 at T0): from the laser's kelvins to overflow in ~650 of these 4000 steps.
  scene.t_end = 4000 * scene.dt;
  thermal::Sinter sinter(bed, scene, test::table_316l());
  EXPECT_THROW(sinter.run(nullptr, 0, nullptr), NumericalError);
  // The implicit integrator takes the same dt and stays finite with the balance closed.
  scene.unsafe_dt = false;
  scene.integrator = thermal::Integrator::implicit_euler;
  scene.t_end = NAN;
  thermal::Sinter implicit(bed, scene, test::table_316l());
  const auto r = implicit.run(nullptr, 0, nullptr);
  expect_finite(implicit, r);
  EXPECT_LT(r.energy.relative_error(), kBalance);
}
