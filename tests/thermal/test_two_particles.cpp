// Two lumped particles exchanging heat through their contact (docs/physics.md §5): with constant
// properties and nothing else on, C1 dT1/dt = G (T2 - T1), C2 dT2/dt = G (T1 - T2), so
// ΔT(t) = ΔT0 exp(-G (1/C1 + 1/C2) t) with G = k π a^2 / d.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "powderbed/thermal/contact_conduction.hpp"
#include "powderbed/thermal/solver.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;
using std::numbers::pi;

namespace {

constexpr double kT0 = 363, kHot = 463;

struct PairRun {
  double difference;  // T1 - T2 at t_end, K
  double sum;         // C1 T1 + C2 T2 at t_end, J
  double analytic;    // ΔT0 exp(-rate t_end)
  double rate_dt;     // rate * dt: forward Euler's step in units of the decay time
  double initial_sum;
};

// An unequal pair (r1 = 20 µm, r2 = 14 µm) overlapping by 10 % of r2, both resting on the
// floor; particle 0 starts at kHot, particle 1 at T0; run for one decay time at step dt.
PairRun run_pair(double dt_fraction) {
  const double r1 = 20e-6, r2 = 14e-6;
  const double z1 = test::resting_z(r1), z2 = test::resting_z(r2);
  const double d = r1 + r2 - 0.1 * r2;
  const double horizontal = std::sqrt(d * d - (z1 - z2) * (z1 - z2));
  bed::Bed bed = test::empty_bed(120e-6, 60e-6, 60e-6);
  bed.add(40e-6, 30e-6, z1, r1);
  bed.add(40e-6 + horizontal, 30e-6, z2, r2);
  thermal::SinterScene scene = test::small_scene(thermal::kConduction, {5, 3, 3}, 60e-6);

  const auto table = test::table_316l();
  double rate = 0, c1 = 0, c2 = 0, bound = 0;
  {
    thermal::Sinter probe(bed, scene, table);
    EXPECT_EQ(probe.network().pairs.size(), 1u);
    const auto& m = probe.material();
    const double k = m.conductivity(kT0), rho = m.density(kT0), c = m.apparent_heat_capacity(kT0);
    const double a = thermal::contact_radius(r1, r2, d);
    const double g = k * pi * a * a / d;
    c1 = rho * 4.0 / 3.0 * pi * r1 * r1 * r1 * c;
    c2 = rho * 4.0 / 3.0 * pi * r2 * r2 * r2 * c;
    rate = g * (1 / c1 + 1 / c2);
    bound = probe.stable_steps().grid;
  }
  // The grid is idle here; the pair is what we time-step, so dt is set from the pair's rate
  // (the coarse grid's bound is above it, so the step is accepted and taken as given).
  scene.dt = dt_fraction / rate;
  EXPECT_LT(scene.dt, bound);
  scene.t_end = 1 / rate;
  thermal::Sinter sinter(bed, scene, table);
  EXPECT_EQ(sinter.substeps(), 1u);
  sinter.set_particle_temperature(0, kHot);
  const double initial_sum = c1 * kHot + c2 * kT0;
  sinter.run(nullptr, 0, nullptr);
  const auto& t = sinter.particle_temperature();
  return {t[0] - t[1], c1 * t[0] + c2 * t[1], (kHot - kT0) * std::exp(-1.0), rate * scene.dt,
          initial_sum};
}

}  // namespace

TEST(TwoParticles, ExponentialExchangeConvergesAtFirstOrder) {
  const PairRun coarse = run_pair(0.02), fine = run_pair(0.01);
  // Forward Euler gives ΔT0 (1 - rate dt)^n: its relative error at rate t = 1 is
  // (rate t)(rate dt)/2 = 1 % and 0.5 % here; 1.2x that allows the O(dt^2) remainder.
  const double e_coarse = std::abs(coarse.difference - coarse.analytic);
  const double e_fine = std::abs(fine.difference - fine.analytic);
  EXPECT_LT(e_coarse, 1.2 * 0.5 * coarse.rate_dt * coarse.analytic);
  EXPECT_LT(e_fine, 1.2 * 0.5 * fine.rate_dt * fine.analytic);
  // First order: halving dt halves the error; the next term is O(dt^2), 1 % of it, so 1.9–2.1.
  EXPECT_GT(e_coarse / e_fine, 1.9) << e_coarse << " " << e_fine;
  EXPECT_LT(e_coarse / e_fine, 2.1) << e_coarse << " " << e_fine;
  // The pair exchanges energy exactly: C1 T1 + C2 T2 is conserved to the enthalpy table's
  // round-off (constant capacity: the table inverts a linear function), 1e-12 relative.
  EXPECT_NEAR(fine.sum, fine.initial_sum, 1e-12 * fine.initial_sum);
}
