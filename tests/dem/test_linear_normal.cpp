// The linear spring–dashpot normal law (linear_normal.hpp, the law of [KE]'s MFiX-DEM beds): its
// kernel on its own, then the solver against the law's closed forms: contact time
// pi / (omega_0 sqrt(1 - zeta^2)), restitution exp(-pi zeta / sqrt(1 - zeta^2)), the static
// overlap m g / k_n, the stable step 1 / omega_0, and the bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "beds.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/linear_normal.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/time_step.hpp"

using namespace powderbed;

namespace {

// [KE]'s stiffness and a steel sphere of 1 mm (their steel 1 mm case).
constexpr double kStiffness = 1e5;  // N/m
constexpr double kRadius = 0.5e-3;  // m
constexpr double kDensity = 7700;   // kg/m^3

dem::Scene linear_scene(unsigned effects, double zeta) {
  dem::Scene s = test::scene_with(effects);
  s.law = dem::ContactLaw::linear;
  s.stiffness = kStiffness;
  s.material.density = kDensity;
  s.material.damping = zeta;
  return s;
}

// Two equal spheres meeting head on at +-v along x; returns the contact's duration and the
// restitution (separation speed over approach speed). dt = 1e-3 / omega_0: a contact of
// pi / 1e-3 ~ 3,100 steps, so the duration is resolved to 3e-4 of itself.
struct HeadOn {
  double duration = 0, restitution = 0;
};
HeadOn head_on(double zeta) {
  const double v = 0.1;
  bed::Bed b = test::box_bed(0.01, 0.01, 0.01);
  test::add_moving(b, 5e-3 - kRadius * 1.001, 5e-3, 5e-3, kRadius, v, 0, 0);
  test::add_moving(b, 5e-3 + kRadius * 1.001, 5e-3, 5e-3, kRadius, -v, 0, 0);
  const dem::Scene scene = linear_scene(dem::kHertz | dem::kDamping, zeta);
  dem::RunSettings s;
  s.dt = 1e-3 * dem::time_step_bound(b, scene, 1).stable;
  s.t_end = 1e-3;
  double first = -1, last = -1;
  s.observer = [&](std::uint64_t, double t, const bed::Bed& bb) {
    const bool contact = bb.x[1] - bb.x[0] < 2 * kRadius;
    if (contact && first < 0) first = t;
    if (contact) last = t;
    return !contact && first >= 0;
  };
  dem::run_deposition(b, scene, s);
  return {last - first, (b.vx[1] - b.vx[0]) / (2 * v)};
}

}  // namespace

TEST(LinearNormal, ForceIsSpringPlusDashpotAndMayPull) {
  const dem::LinearNormalParams p{kStiffness, 0.3};
  const double m_star = 2e-6, delta = 1e-6;
  const dem::LinearPairConstants c = dem::linear_pair_constants(p, m_star);
  // c = 2 zeta sqrt(m* k_n) written out; a few roundings from exact, so DOUBLE_EQ.
  EXPECT_DOUBLE_EQ(c.damping, 2 * 0.3 * std::sqrt(m_star * kStiffness));
  EXPECT_DOUBLE_EQ(dem::linear_elastic_force(c, delta), kStiffness * delta);
  EXPECT_DOUBLE_EQ(dem::linear_damped_force(c, delta, 0.01), kStiffness * delta + c.damping * 0.01);
  // Opening fast, the dashpot outweighs the spring: the law pulls (as MFiX's), unlike Hertz's.
  EXPECT_LT(dem::linear_damped_force(c, delta, -10 * kStiffness * delta / c.damping), 0.0);
  // Energy 1/2 k delta^2: its derivative is the force (central difference, exact for a
  // quadratic up to rounding, so 1e-9 relative).
  const double h = 1e-3 * delta;
  const double dud = (dem::linear_elastic_energy(p, delta + h) -
                      dem::linear_elastic_energy(p, delta - h)) / (2 * h);
  EXPECT_NEAR(dud, kStiffness * delta, 1e-9 * kStiffness * delta);
}

TEST(LinearNormal, ClosedFormsOfTheKernelHeader) {
  // zeta = 0: half a period pi sqrt(m*/k) and full restitution.
  const double m_star = 2e-6;
  EXPECT_DOUBLE_EQ(dem::linear_contact_time({kStiffness, 0.0}, m_star),
                   std::numbers::pi * std::sqrt(m_star / kStiffness));
  EXPECT_DOUBLE_EQ(dem::linear_restitution(0.0), 1.0);
  // zeta = 0.6: sqrt(1 - zeta^2) = 0.8 exactly, e = exp(-0.75 pi).
  EXPECT_NEAR(dem::linear_restitution(0.6), std::exp(-0.75 * std::numbers::pi), 1e-15);
}

TEST(LinearNormal, HeadOnContactTimeAndRestitution) {
  const double mass = test::sphere_mass(kRadius, kDensity);
  for (const double zeta : {0.0, 0.1, 0.3, 0.5}) {
    const HeadOn r = head_on(zeta);
    const double expected = dem::linear_contact_time({kStiffness, zeta}, mass / 2);
    // Resolved to one step (3e-4 of the contact at zeta = 0, less damped ones are longer);
    // Verlet's phase error is (omega dt)^2 / 24 ~ 4e-8. 1e-3 is three steps.
    EXPECT_NEAR(r.duration, expected, 1e-3 * expected) << "zeta = " << zeta;
    // The damping sees the half-step velocity: an O(zeta omega_0 dt) = O(5e-4) error in e at
    // most; 1e-3 is above it and far below a wrong law (zeta off by 1 % moves e by ~5e-3 at
    // zeta = 0.5).
    EXPECT_NEAR(r.restitution, dem::linear_restitution(zeta), 1e-3) << "zeta = " << zeta;
  }
}

TEST(LinearNormal, WallBounceRestitutionAndStaticOverlap) {
  // A sphere dropped on the floor (m* = m): the same e as a pair, independent of m*.
  const double zeta = 0.3, v0 = 0.2;
  {
    bed::Bed b = test::box_bed(0.01, 0.01, 0.01);
    test::add_moving(b, 5e-3, 5e-3, kRadius * 1.001, kRadius, 0, 0, -v0);
    const dem::Scene scene = linear_scene(dem::kWalls | dem::kDamping, zeta);
    dem::RunSettings s;
    s.dt = 1e-3 * dem::time_step_bound(b, scene, 1).stable;
    s.t_end = 1e-3;
    bool touched = false;
    s.observer = [&](std::uint64_t, double, const bed::Bed& bb) {
      touched = touched || bb.z[0] < kRadius;
      return touched && bb.z[0] > kRadius;
    };
    dem::run_deposition(b, scene, s);
    // As in the head-on test: O(zeta omega_0 dt) from the half-step velocity.
    EXPECT_NEAR(b.vz[0] / v0, dem::linear_restitution(zeta), 1e-3);
  }
  {
    // At rest on the floor under gravity the spring carries the weight: delta = m g / k_n.
    bed::Bed b = test::box_bed(0.01, 0.01, 0.01);
    b.add(5e-3, 5e-3, kRadius, kRadius);
    const dem::Scene scene = linear_scene(dem::kGravity | dem::kWalls | dem::kDamping, 0.7);
    dem::RunSettings s;
    s.t_end = 2e-3;  // ~ 300 damping times 1 / (zeta omega_0): the transient is gone
    const auto summary = dem::run_deposition(b, scene, s);
    const double weight = test::sphere_mass(kRadius, kDensity) * scene.gravity;
    // Static balance of a linear spring: exact up to the transient (exp(-300)) and rounding of
    // a 4e-10 m overlap on a 5e-4 m coordinate (1e-16 x 5e-4 / 4e-10 ~ 1e-10 relative); 1e-6.
    EXPECT_NEAR(summary.max_overlap_m, weight / kStiffness, 1e-6 * weight / kStiffness);
    const auto f = dem::wall_forces(b, scene);
    EXPECT_NEAR(f[4], weight, 1e-6 * weight);
  }
}

TEST(LinearNormal, StableStepIsOneOverOmegaOfTheSmallestPair) {
  bed::Bed b = test::box_bed(0.01, 0.01, 0.01);
  b.add(2e-3, 5e-3, 5e-3, kRadius);
  b.add(6e-3, 5e-3, 5e-3, 2 * kRadius);
  const double m = test::sphere_mass(kRadius, kDensity);
  dem::Scene scene = linear_scene(dem::kHertz | dem::kWalls, 0.1);
  auto bound = dem::time_step_bound(b, scene, 1);
  EXPECT_STREQ(bound.limited_by, "contact");
  // Two smallest spheres: m* = m / 2. Same arithmetic, so to rounding.
  EXPECT_DOUBLE_EQ(bound.stable, std::sqrt(m / 2 / kStiffness));
  EXPECT_DOUBLE_EQ(bound.recommended, dem::kTimeStepSafety * bound.stable);
  scene.effects = dem::kWalls;  // only walls: m* = m
  EXPECT_DOUBLE_EQ(dem::time_step_bound(b, scene, 1).stable, std::sqrt(m / kStiffness));
}

TEST(LinearNormal, BadInputIsRefused) {
  EXPECT_EQ(dem::parse_contact_law("linear"), dem::ContactLaw::linear);
  EXPECT_EQ(dem::parse_contact_law("hertz"), dem::ContactLaw::hertz);
  EXPECT_THROW(dem::parse_contact_law("jkr"), InputError);
  for (const double k : {0.0, -1e5, std::nan("")}) {
    dem::Scene scene = linear_scene(dem::kHertz, 0.1);
    scene.stiffness = k;
    EXPECT_THROW(scene.validate(), InputError) << k;
  }
  // The linear law is not softened through E: young-scale is refused with it.
  bed::Bed b = test::box_bed(0.01, 0.01, 0.01);
  b.add(5e-3, 5e-3, 5e-3, kRadius);
  dem::RunSettings s;
  s.t_end = 1e-5;
  s.young_scale = 10;
  EXPECT_THROW(dem::run_deposition(b, linear_scene(dem::kHertz, 0.1), s), InputError);
}
