// Verification of the deposition solver against closed forms (docs/physics.md §4, issue 4): rebound
// height, restitution coefficient, Hertz contact time, Stokes settling, floor force of a column.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "beds.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/hertz_normal.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/stokes_drag.hpp"
#include "powderbed/dem/time_step.hpp"

using namespace powderbed;

namespace {

// e(zeta) from tests/data/hertz_restitution.csv (made by an independent RK4 script).
std::map<double, double> restitution_table() {
  std::ifstream in(std::string(POWDERBED_TEST_DATA) + "/hertz_restitution.csv");
  std::map<double, double> table;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'z') continue;
    std::stringstream s(line);
    double zeta, e;
    char comma;
    s >> zeta >> comma >> e;
    table[std::round(zeta * 100) / 100] = e;
  }
  return table;
}

}  // namespace

TEST(ClosedForms, ElasticDropReboundsToItsHeight) {
  // 20 um 316L sphere, full E, dropped from 100 um above the floor, zeta = 0.
  const double r = 20e-6, h = 100e-6;
  bed::Bed b = test::box_bed(1e-3, 1e-3, 1e-3);
  b.add(5e-4, 5e-4, r + h, r);
  const dem::Scene scene = test::scene_with(dem::kGravity | dem::kWalls);
  dem::RunSettings s;
  s.t_end = 0.02;  // about 2 flight times
  bool bounced = false;
  double top = 0;
  s.observer = [&](std::uint64_t, double, const bed::Bed& bb) {
    if (bb.vz[0] > 0) bounced = true;
    if (bounced) top = std::max(top, bb.z[0]);
    return bounced && bb.vz[0] < 0;  // stop at the apex
  };
  dem::run_deposition(b, scene, s);
  ASSERT_TRUE(bounced);
  // Issue 4 asks 1 %; an elastic Hertz bounce with Verlet at 0.2 t_R returns to within
  // (omega dt)^2 of the energy, far tighter, so 1 % only guards against gross loss.
  EXPECT_NEAR(top - r, h, 0.01 * h);
}

TEST(ClosedForms, RestitutionMatchesIndependentTable) {
  const auto table = restitution_table();
  ASSERT_EQ(table.size(), 21u);
  const double r = 20e-6, v0 = 0.5;
  for (double zeta : {0.1, 0.3, 0.5}) {
    bed::Bed b = test::box_bed(1e-3, 1e-3, 1e-3);
    test::add_moving(b, 5e-4, 5e-4, r * 1.01, r, 0, 0, -v0);
    dem::Scene scene = test::scene_with(dem::kWalls | dem::kDamping);
    scene.material.damping = zeta;
    dem::RunSettings s;
    // 0.01 t_R: about 750 steps per contact, so the O(dt) error at contact onset (where the
    // damping ~ delta^{1/4} is not smooth) stays near 1e-4.
    s.dt = 0.01 * dem::time_step_bound(b, scene, 1).stable;
    s.t_end = 1e-5;
    bool touched = false;
    s.observer = [&](std::uint64_t, double, const bed::Bed& bb) {
      touched = touched || bb.z[0] < r;
      return touched && bb.z[0] > r;  // stop once it has left the floor
    };
    dem::run_deposition(b, scene, s);
    const double e = b.vz[0] / v0;
    // Table to 1e-4; Verlet at 750 steps per contact within ~3e-4 (halving dt moves e by
    // less than that), so 1e-3 separates discretisation from a wrong damping law (zeta off by
    // 1 % moves e by ~2e-3).
    EXPECT_NEAR(e, table.at(zeta), 1e-3) << "zeta = " << zeta;
  }
}

TEST(ClosedForms, HeadOnHertzContactTime) {
  // Two equal 20 um spheres approaching at v = 0.2 m/s each (relative 0.4), hertz only.
  const double r = 20e-6, v = 0.2;
  bed::Bed b = test::box_bed(1e-3, 1e-3, 1e-3);
  test::add_moving(b, 5e-4 - r * 1.001, 5e-4, 5e-4, r, v, 0, 0);
  test::add_moving(b, 5e-4 + r * 1.001, 5e-4, 5e-4, r, -v, 0, 0);
  const dem::Scene scene = test::scene_with(dem::kHertz);
  dem::RunSettings s;
  s.dt = 0.01 * dem::time_step_bound(b, scene, 1).stable;
  s.t_end = 1e-5;
  double first = -1, last = -1;
  s.observer = [&](std::uint64_t, double t, const bed::Bed& bb) {
    const bool contact = bb.x[1] - bb.x[0] < 2 * r;
    if (contact && first < 0) first = t;
    if (contact) last = t;
    return !contact && first >= 0;
  };
  dem::run_deposition(b, scene, s);
  const auto& m = scene.material;
  const double mass = test::sphere_mass(r, m.density);
  const double m_star = mass / 2, r_star = r / 2;
  const double e_star = dem::effective_modulus(m.young, m.poisson, m.young, m.poisson);
  const double expected =
      2.87 * std::pow(m_star * m_star / (r_star * e_star * e_star * 2 * v), 0.2);
  // Issue 4: within 2 % (the coefficient 2.87 is itself rounded from 2.868; the contact
  // duration is resolved to one step, 1/750 of it).
  EXPECT_NEAR(last - first, expected, 0.02 * expected);
}

TEST(ClosedForms, StokesSettlingReachesTerminalVelocity) {
  const double r = 10e-6;
  bed::Bed b = test::box_bed(1e-3, 1e-3, 0.1);
  b.add(5e-4, 5e-4, 0.099, r);
  const dem::Scene scene = test::scene_with(dem::kGravity | dem::kDrag);
  const auto& m = scene.material;
  const double tau = test::sphere_mass(r, m.density) /
                     dem::stokes_drag_coefficient({scene.fluid_viscosity}, r);
  dem::RunSettings s;
  s.t_end = 10 * tau;  // exp(-10) = 4.5e-5 of the start speed difference remains
  s.dt = 0.01 * tau;   // the discrete fixed point is exact; small dt keeps the transient true
  dem::run_deposition(b, scene, s);
  const double terminal = dem::stokes_terminal_speed({scene.fluid_viscosity}, m.density,
                                                     scene.gravity, r);
  // Issue 4: within 0.5 %; the remaining transient is 4.5e-5.
  EXPECT_NEAR(-b.vz[0], terminal, 0.005 * terminal);
}

TEST(ClosedForms, SettledColumnFloorForceEqualsWeight) {
  // Five 20 um spheres stacked on one vertical line (no lateral force can arise), with
  // gaps; softened E (S = 1e3) so the 0.2 t_R step is long; strong damping settles them.
  const double r = 20e-6;
  bed::Bed b = test::box_bed(0.2e-3, 0.2e-3, 0.5e-3);
  for (int k = 0; k < 5; ++k) b.add(1e-4, 1e-4, r + k * 2.2 * r, r);
  dem::Scene scene = test::scene_with(dem::kGravity | dem::kHertz | dem::kDamping | dem::kWalls);
  scene.material.damping = 0.7;
  dem::RunSettings s;
  s.young_scale = 1e3;
  s.until_rest = true;
  s.rest.max_speed = 1e-7;  // velocity damping forces then ~ c v, below 1e-6 of the weight
  s.t_end = 0.05;
  const auto summary = dem::run_deposition(b, scene, s);
  EXPECT_TRUE(summary.at_rest);
  double weight = 0;
  for (double rad : b.radius) weight += test::sphere_mass(rad, scene.material.density) * scene.gravity;
  const auto f = dem::wall_forces(b, scene, s.young_scale);
  // Issue 4: within 0.1 %; at rest the floor carries the weight up to the residual
  // accelerations (speeds < 1e-7 m/s).
  EXPECT_NEAR(f[4], weight, 1e-3 * weight);
  EXPECT_EQ(f[5], 0.0);  // nothing touches the lid
}
