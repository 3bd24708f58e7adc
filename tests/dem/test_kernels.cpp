// Each law of docs/physics.md §4 on its own: Hertz normal force, damping clamp, friction
// regularisation, Stokes drag, the Rayleigh step and the time-step bound.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "beds.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/hertz_normal.hpp"
#include "powderbed/dem/mindlin_tangential.hpp"
#include "powderbed/dem/sliding_friction.hpp"
#include "powderbed/dem/stokes_drag.hpp"
#include "powderbed/dem/time_step.hpp"

using namespace powderbed;

TEST(HertzNormal, ElasticForceStiffnessAndEnergyAgree) {
  const dem::HertzNormalParams p{1e11, 0.0};
  const double r_star = 10e-6, delta = 1e-8;
  // 4/3 E* sqrt(R*) delta^1.5 written out independently.
  EXPECT_DOUBLE_EQ(dem::hertz_elastic_force(p, r_star, delta),
                   4.0 / 3.0 * 1e11 * std::sqrt(10e-6) * std::pow(1e-8, 1.5));
  // Stiffness = dF/d delta and force = dU/d delta by central differences; step 1e-4 delta
  // gives a truncation error ~1e-8 relative, so 1e-6 is far above it and far below a bug.
  const double h = 1e-4 * delta;
  const double dfd = (dem::hertz_elastic_force(p, r_star, delta + h) -
                      dem::hertz_elastic_force(p, r_star, delta - h)) / (2 * h);
  EXPECT_NEAR(dem::hertz_stiffness(p, r_star, delta), dfd, 1e-6 * dfd);
  const double dud = (dem::hertz_elastic_energy(p, r_star, delta + h) -
                      dem::hertz_elastic_energy(p, r_star, delta - h)) / (2 * h);
  EXPECT_NEAR(dem::hertz_elastic_force(p, r_star, delta), dud, 1e-6 * dud);
}

TEST(HertzNormal, DampingAddsTwoZetaSqrtMkAndNeverPulls) {
  const dem::HertzNormalParams p{1e11, 0.3};
  const double r_star = 10e-6, m_star = 1e-10, delta = 1e-8;
  const double fe = dem::hertz_elastic_force(p, r_star, delta);
  const double c = 2 * 0.3 * std::sqrt(m_star * dem::hertz_stiffness(p, r_star, delta));
  EXPECT_DOUBLE_EQ(dem::hertz_damped_force(p, r_star, m_star, delta, 0.01), fe + c * 0.01);
  // Separating fast enough that F_e + c delta' < 0: the contact does not pull (docs/physics.md §4).
  EXPECT_EQ(dem::hertz_damped_force(p, r_star, m_star, delta, -10 * fe / c), 0.0);
}

TEST(HertzNormal, TabulatedPairConstantsGiveTheSameLaw) {
  // The force loop's division-free form a delta^{3/2} + b delta^{1/4} delta' against the
  // direct kernels; both are a few roundings from the exact value, so 1e-14 relative.
  const dem::HertzNormalParams p{1e11, 0.3};
  const double r_star = 7e-6, m_star = 3e-11;
  const dem::HertzPairConstants c = dem::hertz_pair_constants(p, r_star, m_star);
  for (const double delta : {1e-10, 1e-8, 1e-7}) {
    for (const double rate : {-0.05, 0.0, 0.01}) {
      const double direct = dem::hertz_damped_force(p, r_star, m_star, delta, rate);
      EXPECT_NEAR(dem::hertz_damped_force(c, delta, rate), direct, 1e-14 * std::abs(direct));
    }
    const double elastic = dem::hertz_elastic_force(p, r_star, delta);
    EXPECT_NEAR(dem::hertz_elastic_force(c, delta), elastic, 1e-14 * elastic);
  }
}

TEST(SlidingFriction, CoulombWhenSlidingZeroAtRest) {
  const dem::SlidingFrictionParams p{0.1, 1e-5};
  double f[3];
  dem::sliding_friction_force(p, 2.0, 0.3, -0.4, 0.0, f);
  // |v_t| = 0.5 m/s >> v_reg: |F| = mu |F_n| / sqrt(1 + (v_reg/|v_t|)^2) = 0.2 (1 - 2e-10),
  // so Coulomb's 0.2 holds to 4e-11 N; 1e-10 allows that and nothing else.
  EXPECT_NEAR(std::hypot(f[0], f[1], f[2]), 0.2, 1e-10);
  EXPECT_NEAR(f[0], -0.2 * 0.6, 1e-10);  // opposite to the slip
  EXPECT_NEAR(f[1], 0.2 * 0.8, 1e-10);
  dem::sliding_friction_force(p, 2.0, 0.0, 0.0, 0.0, f);
  EXPECT_EQ(std::hypot(f[0], f[1], f[2]), 0.0);
  // At |v_t| = v_reg the force is 1/sqrt(2) of Coulomb: smooth, no jump through zero.
  dem::sliding_friction_force(p, 2.0, 1e-5, 0.0, 0.0, f);
  EXPECT_NEAR(f[0], -0.2 / std::sqrt(2.0), 1e-15);
}

TEST(StokesDrag, CoefficientAndTerminalSpeed) {
  const dem::StokesDragParams p{2.1e-5};
  EXPECT_DOUBLE_EQ(dem::stokes_drag_coefficient(p, 1e-5), 6 * std::numbers::pi * 2.1e-5 * 1e-5);
  // Terminal speed = m g / (6 pi mu r) = (4/3 pi r^3 rho g) / (6 pi mu r).
  const double r = 1e-5, rho = 7952, g = 9.81;
  EXPECT_NEAR(dem::stokes_terminal_speed(p, rho, g, r),
              test::sphere_mass(r, rho) * g / dem::stokes_drag_coefficient(p, r), 1e-12);
}

TEST(TimeStep, RayleighFormulaAndBound) {
  // docs/physics.md §4 with E = 193 GPa, nu = 0.26, rho = 7952, r = 5 um, evaluated by hand:
  // G = 193e9 / 2.52 = 7.6587e10 Pa, sqrt(rho/G) = 3.22225e-4 s/m,
  // t_R = pi 5e-6 3.22225e-4 / (0.1631 0.26 + 0.8766) = 5.50759e-9 s (6 digits: tolerance 1e-14 s).
  EXPECT_NEAR(dem::rayleigh_time_step(5e-6, 7952, 193e9, 0.26), 5.50759e-9, 1e-14);
  bed::Bed b = test::box_bed(1e-3, 1e-3, 1e-3);
  b.add(2e-4, 2e-4, 2e-4, 5e-6);
  b.add(4e-4, 4e-4, 4e-4, 20e-6);
  const dem::Scene scene;  // all effects, drag relaxation (~2 ms) far above t_R
  const auto bound = dem::time_step_bound(b, scene, 1.0);
  EXPECT_DOUBLE_EQ(bound.stable, dem::rayleigh_time_step(5e-6, 7952, 193e9, 0.26));
  EXPECT_DOUBLE_EQ(bound.recommended, dem::kTimeStepSafety * bound.stable);
  // Softening E by S lengthens t_R by sqrt(S).
  EXPECT_NEAR(dem::time_step_bound(b, scene, 100.0).stable, 10 * bound.stable, 1e-12 * bound.stable);
  EXPECT_THROW(dem::time_step_bound(b, scene, 0.0), InputError);
}

TEST(Scene, RejectsNegativeDampingAndContactlessDamping) {
  dem::Scene s;
  s.material.damping = -0.1;
  EXPECT_THROW(s.validate(), InputError);
  dem::Scene t = test::scene_with(dem::kGravity | dem::kDamping);
  EXPECT_THROW(t.validate(), InputError);
}

TEST(MindlinTangential, StiffnessIsEightGStarSqrtRDeltaAndTheConstantFactorsIt) {
  const double e = 193e9, nu = 0.26, r_star = 10e-6, delta = 1e-8;
  const double g = e / (2 * (1 + nu));
  // Two equal materials: 1 / G* = 2 (2 - nu) / G.
  const double g_star = dem::effective_shear_modulus(e, nu, e, nu);
  EXPECT_NEAR(g_star, g / (2 * (2 - nu)), 1e-15 * g_star);  // a few roundings
  EXPECT_DOUBLE_EQ(dem::mindlin_stiffness(g_star, r_star, delta), 8 * g_star * std::sqrt(r_star * delta));
  // The pair constant times delta^{1/2} is the same stiffness up to the roundings of the two
  // roots (1e-15 relative).
  const double k_t = dem::mindlin_stiffness(g_star, r_star, delta);
  EXPECT_NEAR(dem::mindlin_stiffness_constant(g_star, r_star) * std::sqrt(delta), k_t, 1e-15 * k_t);
  // k_t / k_n = 4 G* / E* (Mindlin's ratio; 2 (1 - nu) / (2 - nu) for equal materials), exact
  // to the roundings: 1e-14.
  const double k_n = dem::hertz_stiffness({dem::effective_modulus(e, nu, e, nu), 0.0}, r_star, delta);
  EXPECT_NEAR(k_t / k_n, 2 * (1 - nu) / (2 - nu), 1e-14);
}
