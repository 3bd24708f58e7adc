// Wetting of molten particles (issue 12, point 2; wetting.hpp): the spherical cap a molten
// particle spreads into on the substrate, the exact exchange of two lumped bodies its stiff
// contact is integrated with, and whole passes with effects |= kWetting: the balance closes,
// molten particles wet the substrate and each other, nothing overshoots, and more of the heat
// reaches the substrate than without wetting.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/thermal/contact_temperature.hpp"
#include "powderbed/thermal/solver.hpp"
#include "powderbed/thermal/wetting.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;
using thermal::exact_exchange;
using thermal::spherical_cap;

namespace {

constexpr double kPi = std::numbers::pi;
double degrees(double d) { return d * kPi / 180; }
double sphere_volume(double r) { return 4.0 / 3.0 * kPi * r * r * r; }

// The cap of height H cut from a sphere of radius R, by slices: the disc at height s above the
// sphere's centre has area π (R^2 - s^2), s from R - H to R. Volume and first moment above the
// base (s - (R - H)) are integrals of cubics, which Simpson's rule integrates exactly: the
// values below are exact to round-off, independent of wetting.hpp's closed forms.
struct Slices {
  double volume, centroid_height;
};
Slices cap_by_slices(double big_r, double h) {
  const int n = 64;  // even
  const double s0 = big_r - h, ds = h / n;
  double v = 0, moment = 0;
  for (int q = 0; q <= n; ++q) {
    const double s = s0 + q * ds;
    const double weight = (q == 0 || q == n) ? 1 : (q % 2 ? 4 : 2);
    const double area = kPi * (big_r * big_r - s * s);
    v += weight * area;
    moment += weight * area * (s - s0);
  }
  return {v * ds / 3, moment / v};
}

// Round-off of cbrt, cos, sin and a handful of products: ~1e-15 relative; 1e-12 leaves room
// for the 1/sin θ of recovering R from the base radius at the angles' ends (sin 5° = 0.087)
// and still catches any wrong factor (a cap formula off by one term is off by percents).
constexpr double kRoundOff = 1e-12;

}  // namespace

// ---------------------------------------------------------------------------------------------
// The spherical cap

// The cap keeps the particle's volume: R = a / sin θ and H = R (1 - cos θ) from the returned
// base radius give back V = π H^2 (3 R - H) / 3, for wetting (θ < 90°) and non-wetting
// (θ > 90°) melts and particles from fines to coarse.
TEST(WettingCap, ConservesTheParticleVolume) {
  for (const double r : {2e-6, 13.5e-6, 40e-6})
    for (const double theta : {5.0, 10.0, 30.0, 60.0, 89.0, 90.0, 91.0, 120.0, 150.0, 175.0}) {
      const double v = sphere_volume(r), t = degrees(theta);
      const auto cap = spherical_cap(v, t);
      ASSERT_TRUE(std::isfinite(cap.base_radius) && cap.base_radius > 0) << theta;
      const double big_r = cap.base_radius / std::sin(t), h = big_r * (1 - std::cos(t));
      const double recomputed = kPi * h * h * (3 * big_r - h) / 3;
      // f = 2 - 3 cos θ + cos^3 θ cancels toward θ = 0 (f ≈ 3 θ^4 / 4: 4e-5 at 5°), which
      // spends ~4 eps / f of relative precision on R^3 (2e-11 at 5°, measured 5e-12): that
      // on top of kRoundOff. A wrong formula is off by far more at every angle.
      const double c = std::cos(t), f = 2 - 3 * c + c * c * c;
      const double tolerance = kRoundOff + 4 * 2.2e-16 / f;
      EXPECT_NEAR(recomputed / v, 1.0, tolerance) << "r " << r << " theta " << theta;
      // And by slices (exact for the cubic integrands, see cap_by_slices).
      EXPECT_NEAR(cap_by_slices(big_r, h).volume / v, 1.0, tolerance) << theta;
    }
}

// At θ = 90° the cap is a hemisphere of the sphere's volume: base radius (3 V / 2π)^(1/3) =
// r 2^(1/3); near 90° it tends to it at the rate d ln a / dθ = -1/2 there (from
// a = R sin θ, R ∝ f^(-1/3), f = 2 - 3 cos θ + cos^3 θ: -f'/(3 f) = -1/2 at 90°).
TEST(WettingCap, TendsToAHemisphereAtNinetyDegrees) {
  const double r = 13.5e-6, v = sphere_volume(r);
  const double hemisphere = r * std::cbrt(2.0);
  EXPECT_NEAR(spherical_cap(v, degrees(90)).base_radius / hemisphere, 1.0, kRoundOff);
  for (const double delta : {1e-1, 1e-2, 1e-3, 1e-4, 1e-6})
    for (const double sign : {-1.0, 1.0}) {
      const double a = spherical_cap(v, kPi / 2 + sign * delta).base_radius;
      // First order 0.5 delta; the second-order term is below delta^2 (0.01 delta at 0.1 rad).
      EXPECT_NEAR(a / hemisphere - 1, -0.5 * sign * delta, delta * delta + kRoundOff) << delta;
    }
  // Smaller angles spread wider: the base radius falls monotonically with θ.
  double previous = INFINITY;
  for (double theta = 1; theta < 180; theta += 1) {
    const double a = spherical_cap(v, degrees(theta)).base_radius;
    if (theta <= 90) {
      EXPECT_LT(a, previous) << theta;
    }
    previous = a;
  }
}

// The centroid of a hemisphere lies 3R/8 above its base; for any cap, the slice integral.
TEST(WettingCap, CentroidHeight) {
  const double r = 13.5e-6, v = sphere_volume(r);
  const auto hemi = spherical_cap(v, degrees(90));
  EXPECT_NEAR(hemi.centroid_height / (3.0 / 8.0 * hemi.base_radius), 1.0, kRoundOff);
  for (const double theta : {5.0, 30.0, 60.0, 120.0, 170.0}) {
    const double t = degrees(theta);
    const auto cap = spherical_cap(v, t);
    const double big_r = cap.base_radius / std::sin(t), h = big_r * (1 - std::cos(t));
    const Slices slices = cap_by_slices(big_r, h);
    EXPECT_NEAR(cap.centroid_height / slices.centroid_height, 1.0, kRoundOff) << theta;
    EXPECT_GT(cap.centroid_height, 0.0);
    EXPECT_LT(cap.centroid_height, h);
  }
}

// ---------------------------------------------------------------------------------------------
// The exact exchange of two lumped bodies

namespace {

// Two bodies C1, C2 at T1, T2 joined by G relax to the common temperature
// Tm = (C1 T1 + C2 T2) / (C1 + C2) as T1(t) = Tm + (T1 - Tm) e^{-t/τ}, 1/τ = G (1/C1 + 1/C2):
// the energy into body 1 over dt is C1 (Tm - T1) (1 - e^{-dt/τ}).
double closed_form(double g, double c1, double t1, double c2, double t2, double dt) {
  const double tm = (c1 * t1 + c2 * t2) / (c1 + c2);
  const double rate = g * (1 / c1 + 1 / c2);
  return c1 * (tm - t1) * -std::expm1(-rate * dt);
}

}  // namespace

// Against the closed form, from a conductance far below C/dt (explicit flux) to far above
// (equilibrium within the step).
TEST(WettingExchange, MatchesTwoLumpedBodies) {
  const double c1 = 2.4e-7, c2 = 1.1e-5, t1 = 1800, t2 = 400, dt = 1e-6;  // a fine, a node
  for (double g = 1e-12; g < 1e12; g *= 7.3) {
    const double e = exact_exchange(g, c1, t1, c2, t2, dt);
    const double expected = closed_form(g, c1, t1, c2, t2, dt);
    // Both ~1e-16 relative (expm1, no cancellation); Tm's weighting costs a few ulps of
    // T1 - Tm against the direct G (T2 - T1): 1e-12 relative.
    EXPECT_NEAR(e / expected, 1.0, kRoundOff) << "G " << g;
    EXPECT_LT(e, 0.0);  // the hot body loses
  }
  EXPECT_EQ(exact_exchange(0, c1, t1, c2, t2, dt), 0.0);
  EXPECT_EQ(exact_exchange(1e-3, c1, t1, c2, t1, dt), 0.0);  // no difference, no flow
}

// The series branch for tiny x (x < 1e-8: 1 - x/2, error x^2/6 < 2e-17) joins expm1's.
TEST(WettingExchange, SmallArgumentBranchIsContinuous) {
  const double c1 = 1e-6, c2 = 1e-6, dt = 1.0;
  for (const double x : {1e-12, 0.999e-8, 1e-8, 1.001e-8, 1e-6}) {
    const double g = x / (dt * (1 / c1 + 1 / c2));
    const double phi = exact_exchange(g, c1, 0, c2, 1, dt) / (g * dt);
    EXPECT_NEAR(phi, -std::expm1(-x) / x, 1e-15) << x;
  }
}

// Energy conserved: what body 1 gains body 2 loses, exactly (the same operations on the
// swapped arguments). Exponential relaxation: T1 - Tm shrinks by e^{-x} per step, whatever
// the step, so n steps of dt/n give what one step of dt gives (an explicit flux would not).
TEST(WettingExchange, ConservesEnergyAndRelaxesExponentially) {
  const double c1 = 3e-7, c2 = 5e-6, dt = 1e-6;
  for (const double g : {1e-3, 1.0, 1e3}) {
    double t1 = 1700, t2 = 380;
    const double tm = (c1 * t1 + c2 * t2) / (c1 + c2);
    const double e12 = exact_exchange(g, c1, t1, c2, t2, dt);
    EXPECT_EQ(e12, -exact_exchange(g, c2, t2, c1, t1, dt));
    const double x = g * dt * (1 / c1 + 1 / c2);
    const double one_t1 = t1 + e12 / c1;
    // Relative to T1 - Tm ~ 1e3 K: round-off of T1 + E/C1 (~1e-13 K): 1e-12 of it.
    EXPECT_NEAR((one_t1 - tm) / (t1 - tm), std::exp(-x), kRoundOff) << g;
    for (int step = 0; step < 64; ++step) {
      const double e = exact_exchange(g, c1, t1, c2, t2, dt / 64);
      t1 += e / c1;
      t2 -= e / c2;
    }
    // 64 steps each with its own rounding (~1e-13 K): 1e-10 K on a 1300 K difference.
    EXPECT_NEAR(t1, one_t1, 1e-10) << g;
    EXPECT_NEAR(c1 * t1 + c2 * t2, c1 * 1700 + c2 * 380, 1e-12 * (c1 * 1700 + c2 * 380));
  }
}

// Huge G (a spread cap is far stiffer than the grid step allows an explicit flux to be): both
// bodies land on the common temperature, never beyond it; in between, each temperature stays
// between its start and Tm. A reservoir (the solver's 1e300 for Dirichlet nodes) pulls the
// particle to its own temperature.
TEST(WettingExchange, NeverOvershootsTheCommonTemperature) {
  const double c1 = 2.4e-7, c2 = 1.1e-5, dt = 1e-5;
  for (const auto& [t1, t2] : {std::pair{1800.0, 400.0}, std::pair{363.0, 1750.0}}) {
    const double tm = (c1 * t1 + c2 * t2) / (c1 + c2);
    for (double g = 1e-9; g < 1e40; g *= 10) {
      const double e = exact_exchange(g, c1, t1, c2, t2, dt);
      ASSERT_TRUE(std::isfinite(e)) << g;
      const double n1 = t1 + e / c1, n2 = t2 - e / c2;
      // Beyond Tm by more than rounding (1e-12 of the temperatures) would be an overshoot.
      const double slack = 1e-12 * std::max(t1, t2);
      EXPECT_GE(n1, std::min(t1, tm) - slack) << g;
      EXPECT_LE(n1, std::max(t1, tm) + slack) << g;
      EXPECT_GE(n2, std::min(t2, tm) - slack) << g;
      EXPECT_LE(n2, std::max(t2, tm) + slack) << g;
      if (g * dt * (1 / c1 + 1 / c2) > 50) {  // e^{-50}: equilibrium to round-off
        EXPECT_NEAR(n1, tm, slack) << g;
        EXPECT_NEAR(n2, tm, slack) << g;
      }
    }
  }
  const double e = exact_exchange(1e6, c1, 1800, 1e300, 400, dt);
  EXPECT_NEAR(1800 + e / c1, 400, 1e-9);  // x = 4e4: e^{-x} = 0; 1e-9 K is rounding
}

// ---------------------------------------------------------------------------------------------
// The contact temperature (contact_temperature.hpp)

// Two slabs suddenly in contact, solved by explicit finite volumes: liquid 316L at 2600 K (k 32.4,
// ρ c = 7300 × 815) against a cold, less conductive solid at 363 K (k 14, ρ c = 7900 × 480:
// effusivity 0.52 of the liquid's). The interface (the face value that carries the same flux
// from both sides) must sit at T_c for all t > 0, not at the arithmetic mean (1481 K) nor at
// the conductivity-weighted one. Discretisation: the face value converges as dx / √(κ t);
// at the end the diffusion length spans 40 cells, and 0.5 % of the 2237 K jump (11 K) is
// several times that error while the arithmetic mean is 420 K off.
TEST(ContactTemperature, HoldsTheInterfaceOfTwoSlabsSuddenlyInContact) {
  const double k1 = 32.4, c1 = 7300 * 815.0, t1 = 2600;  // liquid
  const double k2 = 14.0, c2 = 7900 * 480.0, t2 = 363;   // cold solid
  const double tc = thermal::contact_temperature(thermal::effusivity(k1, 7300, 815), t1,
                                                 thermal::effusivity(k2, 7900, 480), t2);
  const int n = 400;  // cells a side
  const double dx = 1e-7;
  const double dt = 0.4 * dx * dx * std::min(c1 / k1, c2 / k2);
  std::vector<double> t(2 * n);
  for (int q = 0; q < 2 * n; ++q) t[q] = q < n ? t1 : t2;
  const auto face = [&] { return (k1 * t[n - 1] + k2 * t[n]) / (k1 + k2); };
  const double kappa = std::max(k1 / c1, k2 / c2);
  const int steps = static_cast<int>(std::ceil(1600 * dx * dx / kappa / dt));  // √(κ t) = 40 dx
  std::vector<double> flux(2 * n + 1, 0.0);
  for (int step = 0; step < steps; ++step) {
    for (int q = 1; q < 2 * n; ++q) {
      const double ka = q - 1 < n ? k1 : k2, kb = q < n ? k1 : k2;
      flux[q] = 2 * ka * kb / (ka + kb) * (t[q - 1] - t[q]) / dx;  // series faces
    }
    for (int q = 0; q < 2 * n; ++q) t[q] += dt * (flux[q] - flux[q + 1]) / dx / (q < n ? c1 : c2);
  }
  std::printf("  T_c %.1f K, finite volumes %.1f K after %d steps (arithmetic mean %.1f K)\n", tc,
              face(), steps, 0.5 * (t1 + t2));
  EXPECT_NEAR(face(), tc, 0.005 * (t1 - t2));
  EXPECT_GT(std::abs(tc - 0.5 * (t1 + t2)), 0.1 * (t1 - t2));  // the test tells the two apart
  // Symmetric in the bodies, and each body's own temperature where the other has no effusivity.
  EXPECT_DOUBLE_EQ(thermal::contact_temperature(2, 1000, 2, 2000), 1500);
  EXPECT_DOUBLE_EQ(thermal::contact_temperature(1, 500, 0, 2000), 500);
}

// ---------------------------------------------------------------------------------------------
// Whole passes

namespace {

void expect_finite(const thermal::Sinter& s, const thermal::SinterResult& r) {
  for (const double t : s.particle_temperature()) EXPECT_TRUE(std::isfinite(t));
  for (const double t : s.substrate_temperature()) EXPECT_TRUE(std::isfinite(t));
  EXPECT_TRUE(std::isfinite(r.max_temperature));
  EXPECT_TRUE(std::isfinite(r.energy.relative_error()));
}

// Heat flows only in from the laser; convection and radiation pull toward T_env = T0 and the
// Dirichlet faces sit at T0: no temperature may fall below T0 (a discrete minimum principle
// that forward Euler within its bound and the exact exchange both keep). An overshooting
// exchange would swing a node or particle below it. Slack: kBelowT0.
// The bimodal bed's pass dips one top node 1.3e-7 K below T0 at t = 4.6 µs with or without
// wetting (the grid's own update, not an exchange): 1e-6 K allows that, and is ten orders
// below the swings of an exchange that overshoots (-1e4 K and below measured, see the Stiff and Fines cases).
constexpr double kBelowT0 = 1e-6;
void expect_no_undershoot(const thermal::Sinter& s, double t0) {
  for (std::size_t i = 0; i < s.particle_temperature().size(); ++i)
    EXPECT_GE(s.particle_temperature()[i], t0 - kBelowT0) << "particle " << i;
  for (std::size_t n = 0; n < s.substrate_temperature().size(); ++n)
    EXPECT_GE(s.substrate_temperature()[n], t0 - kBelowT0) << "node " << n;
}

thermal::SinterScene wetting_scene(thermal::LaserAbsorption absorption, bool wetting) {
  auto scene = test::small_scene(thermal::kAllSinterEffects | (wetting ? thermal::kWetting : 0u),
                                 {15, 9, 7}, 60e-6);
  scene.absorption = absorption;
  scene.rays.rays = 2000;
  scene.power = 300;  // melts the top layer and the floor spheres under the beam
  return scene;
}

}  // namespace

// 300 W over the two-layer lattice: particles melt under the beam, spread on the substrate
// and bridge to their molten neighbours (the lattice's floor spheres touch both). The ledger
// still closes to round-off: the exact exchange hands the substrate what the particle loses.
TEST(WettingSinter, MoltenParticlesWetTheSubstrateAndEachOther) {
  const bed::Bed bed = test::lattice_bed(7, 4, 12.5e-6);
  for (const auto absorption :
       {thermal::LaserAbsorption::ray_trace, thermal::LaserAbsorption::beer_lambert}) {
    const auto scene = wetting_scene(absorption, true);
    thermal::Sinter sinter(bed, scene, test::table_316l());
    // The coldest particle and node over every grid step, not only at the end: an exchange
    // that overshoots swings a temperature below T0 for a step or two.
    double coldest = INFINITY;
    const auto r = sinter.run(
        [&](const thermal::Sinter& s) {
          for (const double t : s.particle_temperature()) coldest = std::min(coldest, t);
          for (const double t : s.substrate_temperature()) coldest = std::min(coldest, t);
        },
        1, nullptr);
    std::printf("  %s: %zu molten, %zu wetted, %zu bridges, T_max %.0f K, coldest %.3f K, "
                "balance %.2e\n",
                absorption == thermal::LaserAbsorption::ray_trace ? "ray-trace" : "beer-lambert",
                r.particles_molten, r.substrate_wetted, r.bridges, r.max_temperature, coldest,
                r.energy.relative_error());
    expect_finite(sinter, r);
    expect_no_undershoot(sinter, scene.initial_temperature);
    EXPECT_GE(coldest, scene.initial_temperature - kBelowT0);  // as expect_no_undershoot
    // As RayTraceSinter.SmallPassClosesTheEnergyBalance: round-off (~1e-15); a wetted
    // contact booked on one side only would show at ~1e-3.
    EXPECT_LT(r.energy.relative_error(), 1e-12);
    EXPECT_GT(r.particles_molten, 0u);
    EXPECT_GT(r.substrate_wetted, 0u);
    EXPECT_GT(r.bridges, 0u);
    EXPECT_LE(r.substrate_wetted, r.particles_molten);  // only molten particles spread
    // No particle passes the top of the vaporisation window (it would have left the bed).
    const auto& pc = scene.phase_change;
    EXPECT_LT(r.peaks.particles, pc.boiling_point + pc.window + 500) << "no runaway";
  }
}

// Fines of 4 µm diameter beside and on 40 µm particles (bimodal_bed) under the ray-traced
// beam with wetting: the fines melt first and their spread caps are the stiffest contacts a
// bed has (StiffWettedContactDoesNotOvershoot has one alone). No step may swing a temperature
// below T0; the balance closes.
TEST(WettingSinter, FinesBesideBigParticlesWetWithoutOvershoot) {
  const bed::Bed bed = test::bimodal_bed(0.2);
  auto scene = wetting_scene(thermal::LaserAbsorption::ray_trace, true);
  scene.power = 200;
  thermal::Sinter sinter(bed, scene, test::table_316l());
  double coldest = INFINITY;
  const auto r = sinter.run(
      [&](const thermal::Sinter& s) {
        for (const double t : s.particle_temperature()) coldest = std::min(coldest, t);
        for (const double t : s.substrate_temperature()) coldest = std::min(coldest, t);
      },
      1, nullptr);
  std::printf("  %zu molten, %zu wetted, %zu bridges, T_max %.0f K, coldest %.9f K, balance "
              "%.2e\n", r.particles_molten, r.substrate_wetted, r.bridges, r.max_temperature,
              coldest, r.energy.relative_error());
  expect_finite(sinter, r);
  EXPECT_LT(r.energy.relative_error(), 1e-12);  // as MoltenParticlesWetTheSubstrateAndEachOther
  EXPECT_GT(r.substrate_wetted, 0u);
  EXPECT_GE(coldest, scene.initial_temperature - kBelowT0);  // as expect_no_undershoot
}

// The same pass with and without wetting: the spread caps conduct the molten particles' heat
// into the substrate, which ends the pass holding more of it.
TEST(WettingSinter, MovesMoreHeatIntoTheSubstrate) {
  const bed::Bed bed = test::lattice_bed(7, 4, 12.5e-6);
  for (const auto absorption :
       {thermal::LaserAbsorption::ray_trace, thermal::LaserAbsorption::beer_lambert}) {
    thermal::SinterResult results[2];
    for (const bool wetting : {false, true}) {
      thermal::Sinter sinter(bed, wetting_scene(absorption, wetting), test::table_316l());
      results[wetting] = sinter.run(nullptr, 0, nullptr);
    }
    const auto& dry = results[0].energy;
    const auto& wet = results[1].energy;
    std::printf("  substrate %.4e J dry, %.4e J wet (+ boundary %.4e, %.4e); particles %.4e, "
                "%.4e J\n", dry.internal_substrate, wet.internal_substrate, dry.boundary,
                wet.boundary, dry.internal_particles, wet.internal_particles);
    EXPECT_EQ(results[0].substrate_wetted, 0u);
    EXPECT_GT(results[1].substrate_wetted, 0u);
    EXPECT_GT(wet.internal_substrate, dry.internal_substrate);
    EXPECT_GT(wet.internal_substrate + wet.boundary, dry.internal_substrate + dry.boundary);
    EXPECT_LT(wet.internal_particles, dry.internal_particles);
  }
}

// The stiff case in isolation: one fine (r = 2 µm) resting on the substrate right over a top
// node (10 µm spacing), the laser on the particles only (Beer–Lambert; laser-substrate off, so
// the substrate is heated through the fine alone). The beam melts it; it spreads into a 30°
// cap (a ≈ 4.3 µm, centroid ≈ 0.4 µm above the base: shape π a^2 / z_c ≈ 1.5e-4 m) that ties
// it to that node (~15 times its capacity) with a time constant C / G ≈ 6e-8 s, far below the
// grid step (~2e-6 s): an explicit flux would swing it past the node's temperature. Once the
// beam has passed, the exact exchange must cool it monotonically, never below T0, and the
// node must never get hotter than the fine that heats it.
TEST(WettingSinter, StiffWettedContactDoesNotOvershoot) {
  bed::Bed bed = test::empty_bed(120e-6, 120e-6, 40e-6);
  const double radius = 2e-6;
  bed.add(60e-6, 60e-6, test::resting_z(radius), radius);
  auto scene = test::small_scene((thermal::kAllSinterEffects & ~thermal::kLaserSubstrate) |
                                     thermal::kWetting,
                                 {13, 13, 7}, 60e-6);
  scene.t_end = 400e-6;  // the beam leaves the domain at ~115 µs: ~140 grid steps of cooling
  thermal::Sinter sinter(bed, scene, test::table_316l());
  const auto& g = sinter.grid();
  const std::size_t under = g.index(6, 6, g.k_plate());
  ASSERT_NEAR(g.x(6), bed.x[0], 1e-12);
  ASSERT_NEAR(g.y(6), bed.y[0], 1e-12);
  // Beer–Lambert's beam reaches sqrt(18.5) w (beer_lambert_laser.hpp): past that, no heating.
  const double w = scene.spot_radius;
  const double passed = (bed.x[0] + 5 * w - (g.x0 - w)) / scene.speed;
  const double t0 = scene.initial_temperature;
  struct Sample {
    double time, particle, node;
  };
  std::vector<Sample> history;
  const auto r = sinter.run(
      [&](const thermal::Sinter& s) {
        history.push_back({s.time(), s.particle_temperature()[0], s.substrate_temperature()[under]});
      },
      1, nullptr);
  double peak_node = 0;
  for (const auto& h : history) peak_node = std::max(peak_node, h.node);
  std::printf("  %zu steps of %.3g s: particle peak %.1f K, final %.3f K; node under it peak "
              "%.3f K; wetted %zu, balance %.2e\n", static_cast<std::size_t>(r.steps), r.dt_grid,
              sinter.particle_max_temperature()[0], history.back().particle, peak_node,
              r.substrate_wetted, r.energy.relative_error());
  expect_finite(sinter, r);
  expect_no_undershoot(sinter, t0);
  EXPECT_EQ(r.substrate_wetted, 1u);
  EXPECT_LT(r.energy.relative_error(), 1e-12);  // as MoltenParticlesWetTheSubstrateAndEachOther
  std::size_t cooling = 0;
  for (std::size_t q = 1; q < history.size(); ++q) {
    const Sample& h = history[q];
    EXPECT_GE(h.particle, t0 - kBelowT0) << "t " << h.time;
    // The node has no other source than the fine: never hotter than it (rounding: 1e-9 K).
    EXPECT_LE(h.node, std::max(h.particle, history[q - 1].particle) + 1e-9) << "t " << h.time;
    if (history[q - 1].time < passed) continue;
    ++cooling;
    EXPECT_LE(h.particle, history[q - 1].particle + 1e-9) << "t " << h.time;  // monotone
  }
  EXPECT_GT(cooling, 50u);
  EXPECT_GT(sinter.particle_max_temperature()[0], scene.phase_change.melting_point);
}

TEST(WettingSinter, RefusesContactAnglesOutsideZeroToPi) {
  const bed::Bed bed = test::lattice_bed(4, 3, 12.5e-6);
  for (const double angle : {0.0, 180.0, -10.0, std::nan("")}) {
    auto scene = wetting_scene(thermal::LaserAbsorption::beer_lambert, true);
    scene.contact_angle = angle;
    EXPECT_THROW(thermal::Sinter(bed, scene, test::table_316l()), InputError) << angle;
  }
  auto scene = wetting_scene(thermal::LaserAbsorption::beer_lambert, true);
  scene.integrator = thermal::Integrator::implicit_euler;
  EXPECT_THROW(thermal::Sinter(bed, scene, test::table_316l()), InputError);
}

// Whether a molten fine spreads on a plate that has not remelted is the contact temperature's
// call, not the plate's: the 2 µm fine of StiffWettedContactDoesNotOvershoot, its plate heated
// through it alone (it stays under 700 K, far below T_m). At 200 W the fine superheats to
// ~2700 K, past the ≈ 2450 K at which its melt puts the interface with that plate at T_m: the
// contact spreads. At 60 W it melts but stays far below that: the contact stays arrested.
TEST(WettingSinter, MeltSpreadsWhereItsInterfaceWithTheSolidReachesTm) {
  bed::Bed bed = test::empty_bed(120e-6, 120e-6, 40e-6);
  const double radius = 2e-6;
  bed.add(60e-6, 60e-6, test::resting_z(radius), radius);
  for (const double power : {60.0, 200.0}) {
    auto scene = test::small_scene((thermal::kAllSinterEffects & ~thermal::kLaserSubstrate) |
                                       thermal::kWetting,
                                   {13, 13, 7}, 60e-6);
    scene.power = power;
    thermal::Sinter sinter(bed, scene, test::table_316l());
    const std::size_t under = sinter.grid().index(6, 6, sinter.grid().k_plate());
    double node_peak = 0;
    const auto r = sinter.run(
        [&](const thermal::Sinter& s) { node_peak = std::max(node_peak, s.substrate_temperature()[under]); },
        1, nullptr);
    const double particle_peak = sinter.particle_max_temperature()[0];
    std::printf("  %.0f W: particle peak %.0f K, node under it peak %.0f K, wetted %zu, arrested "
                "%zu\n", power, particle_peak, node_peak, r.substrate_wetted, r.substrate_arrested);
    const auto& pc = scene.phase_change;
    ASSERT_EQ(r.substrate_wetted, 1u);
    ASSERT_GT(particle_peak, pc.melting_point);
    ASSERT_LT(node_peak, pc.melting_point - 500);  // the plate's own temperature never decides
    if (power > 100) {
      EXPECT_GT(particle_peak, 2600.0);
      EXPECT_EQ(r.substrate_arrested, 0u);
    } else {
      EXPECT_LT(particle_peak, 2300.0);
      EXPECT_EQ(r.substrate_arrested, 1u);
    }
  }
}
