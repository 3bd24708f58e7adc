// The spreading run (spread.hpp): static friction on a slope, rolling resistance, the tool's
// geometry, a blade pushing one sphere or passing over it, particle count over a spread, and a
// continued run against the uninterrupted one, and powder frozen deep under the tool (where it
// stays, that the tool never meets it, and that it leaves the layer as a run without it within
// the seed-to-seed spread).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <unistd.h>

#include "beds.hpp"
#include "small_spread.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/surface_contacts.hpp"
#include "powderbed/dem/hertz_normal.hpp"
#include "powderbed/dem/recoater.hpp"
#include "powderbed/dem/rolling_resistance.hpp"
#include "powderbed/dem/sliding_friction.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/dem/tangential_history.hpp"
#include "powderbed/dem/time_step.hpp"

namespace {

using namespace powderbed;

using test::kRadius;
using test::kYoungScale;
using test::granular_scene;
using test::jittered_supply;
using test::lattice_supply;
using test::small_spread;
using test::strip;
constexpr double kG = 9.81;


double sphere_mass(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r * 7952; }

// Hertz overlap of a sphere resting on the plate under a load: F = 4/3 E* sqrt(r) delta^{3/2}.
double resting_overlap(const dem::Scene& s, double r, double load) {
  const double young = s.material.young / kYoungScale;
  const double e = dem::effective_modulus(young, s.material.poisson, s.wall.young / kYoungScale,
                                          s.wall.poisson);
  return std::pow(load / (4.0 / 3.0 * e * std::sqrt(r)), 2.0 / 3.0);
}

// One sphere resting on the plate of a periodic 1 x 1 x 1 mm box.
bed::Bed one_sphere(const dem::Scene& s, double tilt, double x = 0.5e-3, double r = kRadius) {
  bed::Bed b = test::box_bed(1e-3, 1e-3, 1e-3);
  b.domain.periodic = {true, true, false};
  b.add(x, 0.5e-3, r - resting_overlap(s, r, sphere_mass(r) * kG * std::cos(tilt)), r);
  return b;
}

dem::SpreadSettings granular_run(double t_end, double tilt) {
  dem::SpreadSettings st;
  st.with_tool = false;
  st.young_scale = kYoungScale;
  st.t_end = t_end;
  st.gravity_tilt = tilt;
  return st;
}

// Largest speed over the last part of a run.
double late_speed(bed::Bed& b, const dem::Scene& s, dem::SpreadSettings st, double from) {
  double fastest = 0;
  st.observer = [&](std::uint64_t, double t, const bed::Bed& bed, const std::vector<double>&) {
    if (t >= from) fastest = std::max(fastest, std::hypot(bed.vx[0], bed.vy[0], bed.vz[0]));
    return false;
  };
  dem::run_spread(b, s, st);
  return fastest;
}

TEST(StaticFriction, SphereOnASlopeBelowTheFrictionAngleStandsWhereSlidingCreeps) {
  // tan(theta) = 0.3 below mu = 0.5 and below mu_r = 0.5 (a sphere also needs the rolling
  // resistance to hold the torque m g sin(theta) r, mu_r r m g cos(theta) >= that). Normal,
  // tangential and rolling oscillations decay within ~50 us (zeta = 0.1 at ~3e5 rad/s), so by
  // 3 ms the history model is still to ~1e-17 of its start; the sliding law cannot stand: its
  // force mu F_n v / sqrt(v^2 + v_reg^2) balances m g sin(theta) at v = v_reg q / sqrt(1 - q^2),
  // q = tan(theta) / mu: it creeps at 7.5e-6 m/s.
  const double tilt = std::atan(0.3);
  const dem::Scene history = granular_scene(0.5, 0.5, dem::FrictionModel::history);
  bed::Bed standing = one_sphere(history, tilt);
  EXPECT_LT(late_speed(standing, history, granular_run(4e-3, tilt), 3e-3), 1e-9);
  EXPECT_NEAR(standing.x[0], 0.5e-3, 1e-9);

  const dem::Scene sliding = granular_scene(0.5, 0.5, dem::FrictionModel::sliding);
  bed::Bed creeping = one_sphere(sliding, tilt);
  const double creep = late_speed(creeping, sliding, granular_run(4e-3, tilt), 3e-3);
  // Within 1 %: the creep is steady once the transients have decayed (the rolling spring holds
  // the rotation, so the centre moves at the contact's slip speed).
  const double q = 0.3 / 0.5;
  const double expected = dem::SlidingFrictionParams{}.regularisation_speed * q / std::sqrt(1 - q * q);
  EXPECT_NEAR(creep, expected, 0.01 * expected);
}

TEST(StaticFriction, SphereAboveTheFrictionAngleSlidesAtGTimesSinMinusMuCos) {
  // tan(30 deg) = 0.58 > 7/2 mu = 0.35: the contact slips throughout (a sphere rolls without
  // slipping below that), so the centre accelerates at g (sin - mu cos) along the slope. The
  // force is constant once the normal transient has decayed (~50 us), and velocity Verlet is
  // exact for a constant force: 1e-3 of a covers the decayed transient with a wide margin.
  const double tilt = std::numbers::pi / 6, mu = 0.1;
  for (const auto model : {dem::FrictionModel::history, dem::FrictionModel::sliding}) {
    const dem::Scene s = granular_scene(mu, 0, model);
    bed::Bed b = one_sphere(s, tilt);
    double v1 = 0, v2 = 0;
    dem::SpreadSettings st = granular_run(3e-3, tilt);
    st.observer = [&](std::uint64_t, double t, const bed::Bed& bed, const std::vector<double>&) {
      if (v1 == 0 && t >= 1e-3) v1 = bed.vx[0];
      if (v2 == 0 && t >= 3e-3 - 1e-12) v2 = bed.vx[0];
      return false;
    };
    const dem::SpreadSummary r = dem::run_spread(b, s, st);
    const double expected = kG * (std::sin(tilt) - mu * std::cos(tilt));
    const double t1 = std::ceil(1e-3 / r.dt) * r.dt, t2 = r.sim_time;
    EXPECT_NEAR((v2 - v1) / (t2 - t1), expected, 1e-3 * expected) << dem::friction_model_name(model);
  }
}

// run_deposition runs a drop whose laws need rotation on the spreading engine without a tool:
// the same bed to the bit as run_spread's, on one thread or two; what only the drop solver has
// (RK4) is refused.
TEST(SpreadRun, DropThatNeedsRotationIsTheSpreadingRunWithoutATool) {
  const dem::Scene s = granular_scene(0.5, 0.1, dem::FrictionModel::history);
  bed::Bed spread = test::box_bed(1e-3, 1e-3, 1e-3);
  const double lo[3] = {0, 0, 0}, hi[3] = {1e-3, 1e-3, 1e-3};
  test::add_random(spread, 30, 20e-6, 40e-6, lo, hi, 5);
  const bed::Bed start = spread;
  bed::Bed drop = spread;
  dem::run_spread(spread, s, granular_run(2e-3, 0));
  dem::RunSettings run;
  run.t_end = 2e-3;
  run.young_scale = kYoungScale;
  dem::run_deposition(drop, s, run);
  EXPECT_EQ(drop.x, spread.x);
  EXPECT_EQ(drop.z, spread.z);
  EXPECT_EQ(drop.vz, spread.vz);
  EXPECT_NE(drop.z, start.z);  // it ran
  bed::Bed parallel = start;  // ... on two threads, to the bit
  run.threads = 2;
  run.parallel_min_particles = 0;
  dem::run_deposition(parallel, s, run);
  EXPECT_EQ(parallel.x, drop.x);
  EXPECT_EQ(parallel.vz, drop.vz);
  run.integrator = dem::Integrator::rk4;
  try {
    dem::run_deposition(drop, s, run);
    ADD_FAILURE() << "RK4 accepted for a rotating drop";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material.rolling"), std::string::npos) << e.what();
  }
}

// A rotating drop until rest, with its trajectory: it stops once quiet for the window, well
// before its cap, and its snapshots (read from the whole step's velocities in a copy) leave
// the run's bits as they are without them.
TEST(SpreadRun, RotatingDropStopsAtRestAndItsTrajectoryChangesNothing) {
  const dem::Scene s = granular_scene(0.5, 0.1, dem::FrictionModel::history);
  bed::Bed b = one_sphere(s, 0);
  b.z[0] += 5e-6;  // a short fall onto the plate
  dem::RunSettings run;
  run.young_scale = kYoungScale;
  run.until_rest = true;
  run.t_end = 0.5;
  const dem::RunSummary rest = dem::run_deposition(b, s, run);
  EXPECT_TRUE(rest.at_rest);
  EXPECT_LT(rest.sim_time, 0.05);

  const std::string path =
      (std::filesystem::temp_directory_path() / ("rotating-drop-" + std::to_string(getpid()) + ".h5")).string();
  bed::Bed plain = one_sphere(s, 0), watched = plain;
  dem::RunSettings fixed;
  fixed.young_scale = kYoungScale;
  fixed.t_end = 1e-3;
  dem::run_deposition(plain, s, fixed);
  fixed.trajectory = path;
  fixed.trajectory_every = 1000;
  const dem::RunSummary r = dem::run_deposition(watched, s, fixed);
  EXPECT_EQ(watched.z, plain.z);
  EXPECT_EQ(watched.vz, plain.vz);
  const std::string xmf = path.substr(0, path.size() - 3) + ".xmf";
  std::ifstream in(xmf);
  std::stringstream text;
  text << in.rdbuf();
  std::size_t frames = 0;
  for (auto p = text.str().find("<Time "); p != std::string::npos; p = text.str().find("<Time ", p + 1)) ++frames;
  EXPECT_EQ(frames, r.steps / 1000 + (r.steps % 1000 != 0) + 1);  // step 0, every 1000th, the last
  std::filesystem::remove(path);
  std::filesystem::remove(xmf);
}

TEST(SpreadRun, DragSlowsAFallingSphereAsStokesSays) {
  // A sphere falling from rest in argon: v(t) = g tau (1 - exp(-t / tau)), tau = m / (6 pi mu r)
  // (~19 ms at r = 15 um). Verlet sees the drag at the half-step velocity: an error of order
  // dt / tau ~ 1e-5, so 1e-4 is a wide margin.
  dem::Scene s = granular_scene(0.5, 0, dem::FrictionModel::history);
  s.effects |= dem::kDrag;
  bed::Bed b = test::box_bed(1e-3, 1e-3, 1e-3);
  b.add(0.5e-3, 0.5e-3, 0.9e-3, kRadius);
  dem::SpreadSettings st = granular_run(5e-3, 0);
  const dem::SpreadSummary r = dem::run_spread(b, s, st);
  const double tau = sphere_mass(kRadius) / (6 * std::numbers::pi * s.fluid_viscosity * kRadius);
  const double expected = -kG * tau * (1 - std::exp(-r.sim_time / tau));
  EXPECT_NEAR(b.vz[0], expected, 1e-4 * std::abs(expected));
}

TEST(RollingResistance, RollingSphereStopsWithinTheConstantTorqueDistance) {
  // A sphere rolling at v0 on the plate under the capped torque mu_r r m g decelerates at
  // a = mu_r g r arm / (I + m arm^2) = 5/7 mu_r g (arm = r less the overlap, 1e-5 of r), so it
  // stops after v0^2 / (2 a) = 7 v0^2 / (10 mu_r g). 1 % covers the spring's loading (a rotation
  // of cap / k_r ~ 1e-4 rad) and the normal transient at the start.
  const double mu_r = 0.05, v0 = 0.01;
  const dem::Scene s = granular_scene(0.5, mu_r, dem::FrictionModel::history);
  bed::Bed b = test::box_bed(4e-3, 1e-3, 1e-3);
  b.domain.periodic = {true, false, false};  // y walls 0.5 mm away: never touched
  const double delta = resting_overlap(s, kRadius, sphere_mass(kRadius) * kG);
  test::add_moving(b, 0.5e-3, 0.5e-3, kRadius - delta, kRadius, v0, 0, 0);
  dem::SpreadState spin;  // rolling, not sliding, from the start: omega_y = v0 / arm
  dem::SpreadSettings st = granular_run(0.04, 0);
  double farthest = 0;
  bool stopped = false;
  st.observer = [&](std::uint64_t, double, const bed::Bed& bed, const std::vector<double>&) {
    farthest = std::max(farthest, bed.x[0]);
    stopped = stopped || bed.vx[0] < 1e-6 * v0;
    return stopped;
  };
  spin.wx = {0};
  spin.wy = {v0 / (kRadius - delta)};
  spin.wz = {0};
  spin.wall_history.assign(dem::kWallHistoryValues, 0.0);
  spin.dt = 0.2 * dem::rayleigh_time_step(kRadius, 7952, s.material.young / kYoungScale, 0.26);
  dem::run_spread(b, s, st, &spin);
  ASSERT_TRUE(stopped);
  const double expected = 7 * v0 * v0 / (10 * mu_r * kG);
  EXPECT_NEAR(farthest - 0.5e-3, expected, 0.01 * expected);
}

TEST(RecoaterGeometry, SharpAndRoundedBladeEdgesAndTheRollerCircle) {
  dem::Recoater blade;
  blade.thickness = 100e-6;
  const dem::ToolProfile sharp = dem::tool_profile(blade, 50e-6);
  dem::ToolContact c;
  // In front of the face, 10 um below the bottom edge: the contact is the edge itself, at
  // sqrt(5^2 + 10^2) um from the centre.
  ASSERT_TRUE(dem::tool_contact(sharp, 55e-6, 40e-6, 12e-6, c));
  EXPECT_NEAR(c.delta, 12e-6 - std::hypot(5e-6, 10e-6), 1e-15);
  EXPECT_NEAR(c.n[0], -5 / std::hypot(5.0, 10.0), 1e-12);
  EXPECT_NEAR(c.n[2], 10 / std::hypot(5.0, 10.0), 1e-12);
  // Level with the face: a flat contact along -x.
  ASSERT_TRUE(dem::tool_contact(sharp, 55e-6, 80e-6, 10e-6, c));
  EXPECT_NEAR(c.delta, 5e-6, 1e-15);
  EXPECT_DOUBLE_EQ(c.n[0], -1);
  // Under the bottom face, pushed down.
  ASSERT_TRUE(dem::tool_contact(sharp, 0, 45e-6, 10e-6, c));
  EXPECT_NEAR(c.delta, 5e-6, 1e-15);
  EXPECT_DOUBLE_EQ(c.n[2], 1);
  // A 10 um edge radius takes the corner away: the core corner is (40, 60) um, 25 um from
  // the centre, 15 um from the surface, more than the radius.
  blade.edge_radius = 10e-6;
  const dem::ToolProfile round = dem::tool_profile(blade, 50e-6);
  EXPECT_FALSE(dem::tool_contact(round, 55e-6, 40e-6, 12e-6, c));
  EXPECT_DOUBLE_EQ(dem::tool_half_extent(round), 50e-6);
  ASSERT_TRUE(dem::tool_contact(round, 55e-6, 40e-6, 16e-6, c));
  EXPECT_NEAR(c.delta, 1e-6, 1e-15);
  dem::Recoater roller;
  roller.shape = dem::ToolShape::roller;
  roller.radius = 1e-3;
  const dem::ToolProfile circle = dem::tool_profile(roller, 50e-6);
  ASSERT_TRUE(dem::tool_contact(circle, 0, 45e-6, 10e-6, c));  // under the axis
  EXPECT_NEAR(c.delta, 5e-6, 1e-15);
  EXPECT_NEAR(c.surface[2], 50e-6, 1e-15);
}

// A 2 x 0.5 x 1 mm box with a blade 200 um thick from x = 0.3 to 1.2 mm.
dem::SpreadSettings blade_run(double gap) {
  dem::SpreadSettings st;
  st.young_scale = kYoungScale;
  st.tool.thickness = 200e-6;
  st.tool.gap = gap;
  st.tool.speed = 0.1;
  st.tool.start = 0.3e-3;
  st.tool.end = 1.2e-3;
  return st;
}

bed::Bed sphere_on_plate(const dem::Scene& s, double x, double r) {
  bed::Bed b = test::box_bed(2e-3, 0.5e-3, 1e-3);  // side walls 0.25 mm away: never touched
  b.add(x, 0.25e-3, r - resting_overlap(s, r, sphere_mass(r) * kG), r);
  return b;
}

TEST(Recoater, BladePushesASphereTallerThanTheGapAndLeavesNoneBehind) {
  // A 40 um sphere resting on the plate (centre 20 um up). Sharp edge, 30 um gap: the edge
  // meets the sphere 10 um below its centre's height, the contact normal 30 deg below the
  // horizontal, which pushes it forwards (and a little down) all the way. Edge radius 10 um,
  // 10 um gap: the rounding starts at the centre's height, so the push is horizontal. (A normal
  // steeper than the friction angle wedges the sphere against the plate, and the softened
  // contact lets the blade squeeze it through: docs/deposit-spread.md "Tool edges".)
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  for (const auto& [edge, gap] : {std::pair{0.0, 30e-6}, std::pair{10e-6, 10e-6}}) {
    bed::Bed b = sphere_on_plate(s, 0.6e-3, 20e-6);
    dem::SpreadSettings st = blade_run(gap);
    st.tool.edge_radius = edge;
    double worst_lag = -1;  // how far the sphere's centre fell behind the blade's front face
    st.observer = [&](std::uint64_t, double t, const bed::Bed& bed, const std::vector<double>&) {
      const double front = std::min(st.tool.end, st.tool.start + st.tool.speed * t) + 100e-6;
      worst_lag = std::max(worst_lag, front - bed.x[0]);
      return false;
    };
    const dem::SpreadSummary r = dem::run_spread(b, s, st);
    // It never gets behind the face (a sphere that passed under the edge would lag by > r).
    EXPECT_LT(worst_lag, 0.0) << "edge radius " << edge;
    EXPECT_GT(b.x[0], st.tool.end + 100e-6) << "edge radius " << edge;
    EXPECT_GT(r.layers[0].max_tool_force, 0);
    EXPECT_EQ(r.layers[0].lost, 0u);
  }
}

TEST(Recoater, SphereUnderTheGapPassesUntouched) {
  // A 20 um sphere under a 30 um gap: the blade never touches it, so it stays where it rests
  // (no other force has an x component: 1e-15 m is rounding).
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  bed::Bed b = sphere_on_plate(s, 0.6e-3, 10e-6);
  const double x0 = b.x[0];
  dem::SpreadSettings st = blade_run(30e-6);
  double largest = 0;
  st.tool_force_every = 1;
  st.tool_force = [&](const dem::ToolForceSample& f) {
    largest = std::max(largest, std::hypot(f.force[0], f.force[1], f.force[2]));
  };
  const dem::SpreadSummary r = dem::run_spread(b, s, st);
  EXPECT_EQ(largest, 0.0);
  EXPECT_EQ(r.layers[0].max_tool_force, 0.0);
  EXPECT_NEAR(b.x[0], x0, 1e-15);
}

// A supply of spheres of radius 15 um on a cubic lattice of pitch 32 um filling the region.



TEST(Recoater, SpreadKeepsEveryParticle) {
  // None lost through the plate or the tool; with the overflow removed, every particle is
  // either in the bed or counted as overflow.
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  dem::SpreadSettings st = small_spread();
  st.remove_overflow = false;
  bed::Bed b = strip();
  const dem::SpreadSummary r = dem::run_spread(b, s, st);
  ASSERT_EQ(r.layers.size(), 1u);
  EXPECT_GT(r.layers[0].supplied, 100u);
  EXPECT_EQ(b.n(), r.layers[0].supplied);
  EXPECT_EQ(r.layers[0].lost, 0u);
  EXPECT_EQ(r.layers[0].overflow, 0u);
  const double front = st.tool.end + 0.5 * st.tool.thickness;
  std::size_t past = 0;
  for (std::size_t i = 0; i < b.n(); ++i) {
    EXPECT_GT(b.z[i], 0);
    EXPECT_TRUE(b.x[i] >= 0 && b.x[i] <= 1.5e-3);
    past += b.x[i] > front ? 1 : 0;
  }
  EXPECT_GT(past, 0u);  // the excess, pushed to the end
  // The blade left a layer behind it: some powder under the gap past the supply's back.
  EXPECT_GT(r.layers[0].density_under_gap, 0.05);

  bed::Bed c = strip();
  const dem::SpreadSummary with = dem::run_spread(c, s, small_spread());
  EXPECT_EQ(with.layers[0].overflow, past);  // the same run up to the removal
  EXPECT_EQ(c.n() + with.layers[0].overflow, with.layers[0].supplied);
  for (std::size_t i = 0; i < c.n(); ++i) EXPECT_LE(c.x[i], front);
}

// Every particle's forces are summed in one order on any number of threads: a layer gives the
// same bed, state and tool force bit for bit on 1 and 2 threads. parallel_min_particles 0 puts
// this small bed on the threads (two: more than the machine's cores would make each barrier
// wait for a descheduled thread).
TEST(Recoater, SameBedBitForBitOnAnyNumberOfThreads) {
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  const auto spread = [&](int threads) {
    dem::SpreadSettings st = small_spread();
    st.threads = threads;
    st.parallel_min_particles = 0;
    st.tool.end = 0.5e-3;  // the blade through the heap: contacts with the tool, walls and pairs
    bed::Bed b = strip();
    const dem::SpreadSummary r = dem::run_spread(b, s, st);
    return std::pair{b, r};
  };
  const auto [one, r1] = spread(1);
  ASSERT_GT(one.n(), 100u);
  const auto [two, r2] = spread(2);
  EXPECT_EQ(two.x, one.x);
  EXPECT_EQ(two.z, one.z);
  EXPECT_EQ(two.vx, one.vx);
  EXPECT_EQ(r2.state.wy, r1.state.wy);
  EXPECT_EQ(r2.state.pair_history, r1.state.pair_history);
  EXPECT_EQ(r2.state.wall_history, r1.state.wall_history);
  EXPECT_EQ(r2.layers[0].max_tool_force, r1.layers[0].max_tool_force);
}

TEST(Recoater, ContinuedRunEqualsTheUninterruptedOneBitForBit) {
  // The excess kept (no overflow removal), so that the heap's pair contacts carry history
  // across the restart (deposit's test, DepositSpread.*, runs it with the removal).
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  dem::SpreadSettings two = small_spread();
  two.remove_overflow = false;
  two.layers = 2;
  bed::Bed whole = strip();
  const dem::SpreadSummary straight = dem::run_spread(whole, s, two);

  dem::SpreadSettings one = small_spread();
  one.remove_overflow = false;
  bed::Bed first = strip();
  const dem::SpreadSummary half = dem::run_spread(first, s, one);
  // Through the file, as deposit --in does.
  const std::string path =
      (std::filesystem::temp_directory_path() / ("spread-restart-" + std::to_string(getpid()) + ".h5")).string();
  dem::write_spread_bed(path, first, half.state);
  ASSERT_TRUE(dem::has_spread_state(path));
  bed::Bed again = bed::read_bed_h5(path);
  const dem::SpreadState state = dem::read_spread_state(path, again);
  std::filesystem::remove(path);
  std::filesystem::remove(path.substr(0, path.size() - 3) + ".xmf");
  EXPECT_EQ(state.layers_done, 1u);
  EXPECT_GT(state.pair_ids.size(), 0u);
  const dem::SpreadSummary rest = dem::run_spread(again, s, one, &state);
  ASSERT_EQ(rest.layers.size(), 1u);
  EXPECT_EQ(rest.layers[0].layer, 2u);
  ASSERT_EQ(again.n(), whole.n());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < whole.n(); ++i) {
    differ += (again.x[i] != whole.x[i] || again.y[i] != whole.y[i] || again.z[i] != whole.z[i] ||
               again.vx[i] != whole.vx[i] || again.vz[i] != whole.vz[i] ||
               rest.state.wy[i] != straight.state.wy[i] || again.id[i] != whole.id[i]) ? 1 : 0;
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(rest.state.step, straight.state.step);
  EXPECT_EQ(rest.state.pair_history, straight.state.pair_history);
}

// Three layers of small_spread with the overflow kept and the powder more than `depth` below
// the tool's bottom frozen at each layer's start.
dem::SpreadSettings frozen_spread(std::uint64_t layers, double depth) {
  dem::SpreadSettings st = small_spread();
  st.remove_overflow = false;
  st.layers = layers;
  st.freeze_depth = depth;
  return st;
}

TEST(Recoater, FrozenPowderStaysPutAndHoldsThePowderOnIt) {
  // Layer 3's tool bottom is at 60 + 2 x 30 um; with depth 60 um every centre below 60 um is
  // frozen at its start: it must end the layer exactly where it began, at rest, and the
  // powder spread on it must stay above it (none lost through it).
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  const double depth = 60e-6, level = 60e-6 + 2 * 30e-6 - depth;
  dem::SpreadSettings st = frozen_spread(3, depth);
  std::map<std::uint64_t, std::array<double, 3>> before;  // by id, after layer 2
  st.layer_done = [&](const dem::LayerSummary& l, const bed::Bed& bed, const dem::SpreadState&) {
    if (l.layer != 2) return;
    for (std::size_t i = 0; i < bed.n(); ++i) before[bed.id[i]] = {bed.x[i], bed.y[i], bed.z[i]};
  };
  bed::Bed b = strip();
  const dem::SpreadSummary r = dem::run_spread(b, s, st);
  ASSERT_EQ(r.layers.size(), 3u);
  EXPECT_EQ(r.layers[0].frozen, 0u);  // layer 1's level, 60 - 60 um, lies below every centre
  EXPECT_GT(r.layers[1].frozen, 0u);  // layer 2's, 30 um: the spheres on the plate
  std::size_t frozen = 0;
  for (std::size_t i = 0; i < b.n(); ++i) {
    const auto it = before.find(b.id[i]);
    if (it == before.end() || !(it->second[2] < level)) continue;
    ++frozen;
    EXPECT_EQ(b.x[i], it->second[0]);
    EXPECT_EQ(b.y[i], it->second[1]);
    EXPECT_EQ(b.z[i], it->second[2]);
    EXPECT_EQ(std::hypot(b.vx[i], b.vy[i], b.vz[i]), 0.0);
  }
  EXPECT_GT(frozen, 20u);
  EXPECT_EQ(r.layers[2].frozen, frozen);
  EXPECT_EQ(r.layers[2].lost, 0u);
  EXPECT_EQ(b.n(), r.layers[0].supplied + r.layers[1].supplied + r.layers[2].supplied);
}

TEST(Recoater, ContinuedRunWithFrozenPowderEqualsTheUninterruptedOne) {
  // The frozen set is decided at each layer's start from the positions, so a run continued
  // from layer 2's state freezes the same particles in layer 3 as the uninterrupted run.
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  bed::Bed whole = strip();
  const dem::SpreadSummary straight = dem::run_spread(whole, s, frozen_spread(3, 60e-6));
  ASSERT_GT(straight.layers[2].frozen, 0u);
  bed::Bed part = strip();
  const dem::SpreadSummary first = dem::run_spread(part, s, frozen_spread(2, 60e-6));
  const dem::SpreadSummary rest = dem::run_spread(part, s, frozen_spread(1, 60e-6), &first.state);
  EXPECT_EQ(rest.layers[0].frozen, straight.layers[2].frozen);
  ASSERT_EQ(part.n(), whole.n());
  EXPECT_EQ(test::particles_differing(part, rest, whole, straight), 0u);
  EXPECT_EQ(rest.state.pair_history, straight.state.pair_history);
}

TEST(Recoater, ToolMeetingFrozenPowderIsCounted) {
  // Frozen at 60 um under the tool no sphere (radius 15 um) reaches it: the count is 0. Frozen
  // at 1 um, layer 2's supply, lying on layer 1's powder with its lowest centres under the
  // tool's bottom, freezes in the tool's path: the tool passes through it and the run counts it.
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  bed::Bed sound = strip();
  const dem::SpreadSummary deep = dem::run_spread(sound, s, frozen_spread(3, 60e-6));
  ASSERT_GT(deep.layers[2].frozen, 0u);
  for (const dem::LayerSummary& l : deep.layers) EXPECT_EQ(l.frozen_tool_contacts, 0u) << "layer " << l.layer;
  bed::Bed shallow = strip();
  const dem::SpreadSummary touched = dem::run_spread(shallow, s, frozen_spread(2, 1e-6));
  EXPECT_GT(touched.layers[1].frozen_tool_contacts, 0u);
}


// The density under the gap (LayerSummary::density_under_gap) after `layers` layers of
// small_spread with its overflow removed in the chamber (SpreadSettings::chamber) on the jittered
// supply of `seed`, the powder more than `depth` under the tool frozen (0: none).
double chamber_density(const dem::Scene& s, std::uint64_t seed, std::uint64_t layers, double depth) {
  dem::SpreadSettings st = small_spread();
  st.chamber = true;
  st.layers = layers;
  st.freeze_depth = depth;
  st.supply = jittered_supply(seed);
  bed::Bed b = strip();
  return dem::run_spread(b, s, st).layers.back().density_under_gap;
}

TEST(Recoater, FrozenPowderLeavesTheLayerDensityWithinTheSeedSpread) {
  // Layer 3 freezes the centres below 60 um (two sphere diameters under its tool; a fourth
  // layer's supply would reach behind the tool's start in this strip): its density under the
  // gap, averaged over three seeds, must differ from the runs without freezing by no more than
  // those runs differ among themselves (their range over the seeds): a bias of freezing larger
  // than a change of seed fails. (The solid over the far half of the travel is not within it:
  // docs/results/spread-layers.md "Sleeping by default".)
  const dem::Scene s = granular_scene(0.5, 0.05, dem::FrictionModel::history);
  double lo = 1, hi = 0, mean_moving = 0, mean_frozen = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const double moving = chamber_density(s, seed, 3, 0.0);
    lo = std::min(lo, moving);
    hi = std::max(hi, moving);
    mean_moving += moving / 3.0;
    mean_frozen += chamber_density(s, seed, 3, 60e-6) / 3.0;
  }
  EXPECT_GT(hi - lo, 0.0);  // the seeds do differ
  EXPECT_LE(std::abs(mean_frozen - mean_moving), hi - lo) << mean_frozen << " against " << mean_moving;
}

TEST(Recoater, BadToolOrSupplyIsRefused) {
  const dem::Scene s = granular_scene(0.5, 0, dem::FrictionModel::history);
  {
    dem::SpreadSettings st = small_spread();
    st.tool.gap = 0;
    bed::Bed b = strip();
    EXPECT_THROW(dem::run_spread(b, s, st), InputError);
  }
  {  // a particle where the blade starts
    dem::SpreadSettings st = small_spread();
    bed::Bed b = strip();
    b.add(0.1e-3, 0.15e-3, 0.2e-3, kRadius);
    EXPECT_THROW(dem::run_spread(b, s, st), InputError);
  }
  {  // a supply taller than the box
    dem::SpreadSettings st = small_spread();
    st.supply_height = 1e-3;
    bed::Bed b = strip();
    EXPECT_THROW(dem::run_spread(b, s, st), InputError);
  }
  {  // a negative freezing depth
    dem::SpreadSettings st = small_spread();
    st.freeze_depth = -1e-6;
    bed::Bed b = strip();
    EXPECT_THROW(dem::run_spread(b, s, st), InputError);
  }
  {  // a supply behind the blade's front
    dem::SpreadSettings st = small_spread();
    st.supply_x0 = 0.12e-3;
    bed::Bed b = strip();
    EXPECT_THROW(dem::run_spread(b, s, st), InputError);
  }
}

TEST(TangentialHistory, SpringHoldsBelowTheCapAndSlidesAtIt) {
  const dem::TangentialSpring k{100.0, 0.0};
  double spring[3] = {0, 0, 0}, f[3];
  const double vt[3] = {1e-3, 0, 0};
  dem::tangential_history_force(k, 0.5, 1.0, vt, 1e-3, true, spring, f);  // 1 um of slip
  EXPECT_DOUBLE_EQ(f[0], -100.0 * 1e-6);
  for (int s = 0; s < 10000; ++s) dem::tangential_history_force(k, 0.5, 1.0, vt, 1e-3, true, spring, f);
  EXPECT_DOUBLE_EQ(f[0], -0.5);       // Coulomb: mu F_n
  EXPECT_DOUBLE_EQ(spring[0], -0.5);  // the spring reset to the cap
  const double still[3] = {0, 0, 0};
  dem::tangential_history_force(k, 0.5, 1.0, still, 1e-3, true, spring, f);
  EXPECT_DOUBLE_EQ(f[0], -0.5);  // stops slipping: holds
  double turned[3] = {3, 4, 0};
  const double n[3] = {0, 1, 0};
  dem::rotate_onto_tangent_plane(turned, n);
  EXPECT_DOUBLE_EQ(turned[0], 5);  // length kept
  EXPECT_DOUBLE_EQ(turned[1], 0);
}

// A contact at rest turns by less than 1e-6 rad a step, where the turn keeps the length only to
// along^2 / 2 a step (tangential_history.hpp): a spring turned by 0.9e-6 rad a step for a
// million steps (0.9 rad in all) keeps its length within the documented 1e-6. Turned by 2e-6 rad
// a step it is rescaled every step and keeps it to round-off (1e-9 for a million steps; the
// projection alone would lose 2e-6).
TEST(TangentialHistory, SpringTurnedInSmallStepsKeepsItsLength) {
  for (const auto& [turn, tolerance] : {std::pair{0.9e-6, 1e-6}, std::pair{2e-6, 1e-9}}) {
    double spring[3] = {1, 0, 0};
    double n[3] = {0, 0, 1};
    for (int s = 1; s <= 1000000; ++s) {
      const double a = turn * s;  // the normal turns about y
      n[0] = std::sin(a);
      n[2] = std::cos(a);
      dem::rotate_onto_tangent_plane(spring, n);
    }
    const double length = std::sqrt(spring[0] * spring[0] + spring[1] * spring[1] + spring[2] * spring[2]);
    EXPECT_NEAR(length, 1.0, tolerance) << "turn " << turn << " rad a step";
    EXPECT_NEAR(spring[0] * n[0] + spring[1] * n[1] + spring[2] * n[2], 0.0, 1e-15);
  }
}

}  // namespace

// The solid of earlier layers as the floor (SpreadSettings::floor, build): a sphere dropped over
// a block raised 20 um comes to rest on it, at the block's height plus its radius less the Hertz
// overlap of its weight (to 1 % of that overlap); on a slope of the height map its contact
// pushes along the surface's normal, so a frictionless sphere slides downhill.
TEST(SpreadFloor, SphereRestsOnTheRaisedSolidAndSlidesDownItsSlope) {
  const dem::Scene s = granular_scene(0.5, 0.0, dem::FrictionModel::history);
  bed::HeightMap floor;
  floor.nx = floor.ny = 11;
  floor.dx = floor.dy = 1e-4;
  floor.z.assign(floor.nx * floor.ny, 20e-6);
  bed::Bed b = one_sphere(s, 0.0);
  b.z[0] += 40e-6;  // above the block, falling onto it
  dem::SpreadSettings st = granular_run(30e-3, 0.0);
  st.floor = floor;
  dem::run_spread(b, s, st);
  const double rest = 20e-6 + kRadius - resting_overlap(s, kRadius, sphere_mass(kRadius) * kG);
  EXPECT_NEAR(b.z[0], rest, 0.01 * (kRadius + 20e-6 - rest));
  EXPECT_LT(std::hypot(b.vx[0], b.vy[0], b.vz[0]), 1e-4);
  // A ramp rising along +x (slope 0.2): without friction the sphere moves towards -x.
  const dem::Scene slick = granular_scene(0.0, 0.0, dem::FrictionModel::sliding);
  for (std::size_t j = 0; j < floor.ny; ++j)
    for (std::size_t i = 0; i < floor.nx; ++i) floor.z[i + floor.nx * j] = 0.2 * floor.dx * static_cast<double>(i);
  bed::Bed ramp = one_sphere(slick, 0.0);
  ramp.z[0] = floor.at(ramp.x[0], ramp.y[0]) + 1.05 * kRadius * std::sqrt(1.04);
  const double x0 = ramp.x[0];
  dem::SpreadSettings sr = granular_run(2e-3, 0.0);
  sr.floor = floor;
  dem::run_spread(ramp, slick, sr);
  EXPECT_LT(ramp.x[0], x0 - 1e-6);
  // A floor outside the box is refused.
  floor.z[0] = -1e-6;
  sr.floor = floor;
  EXPECT_THROW(dem::run_spread(ramp, slick, sr), InputError);
}

namespace {

// A V-shaped groove along y in the floor of a periodic 0.2 x 0.2 mm box: slopes of 0.3 either
// side of x = 0.1 mm, on a 10 um grid, and one sphere of 15 um dropped into it 3 um off its line.
bed::HeightMap groove() {
  bed::HeightMap m;
  m.nx = m.ny = 21;
  m.dx = m.dy = 10e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.z.push_back(50e-6 + 0.3 * std::abs(10e-6 * static_cast<double>(i) - 100e-6));
  return m;
}

bed::Bed sphere_over_groove() {
  bed::Bed b = test::box_bed(0.2e-3, 0.2e-3, 0.4e-3);
  b.domain.periodic = {true, true, false};
  b.add(103e-6, 97e-6, 73e-6, kRadius);
  return b;
}

}  // namespace

// In a groove a sphere touches both slopes (bed/surface_contacts.hpp) and comes to rest at its
// bottom: with the build scenes' friction and rolling resistance its speed is under 1e-9 m/s
// after 15 ms (measured: 5e-12 m/s at 12 ms). The single contact at the nearest of 25 sampled
// points that this replaced held it by one slope at a time: it chattered at 2e-6 to 6e-6 m/s
// from 12 ms to 20 ms (docs/build.md "Limits").
TEST(SpreadFloor, SphereInAGrooveTouchesBothSlopesAndComesToRest) {
  const dem::Scene s = granular_scene(0.5, 0.1, dem::FrictionModel::history);
  bed::Bed b = sphere_over_groove();
  dem::SpreadSettings st = granular_run(20e-3, 0.0);
  st.young_scale = 1e4;  // the build scene's
  st.floor = groove();
  EXPECT_LT(late_speed(b, s, st, 15e-3), 1e-9);
  EXPECT_NEAR(b.x[0], 100e-6, 1e-8);  // on the groove's line
}

// Along a periodic axis the floor must span the box (its seam is the box's): half the groove in
// the periodic box is refused, naming the axis.
TEST(SpreadFloor, FloorNotSpanningAPeriodicAxisIsRefused) {
  const dem::Scene s = granular_scene(0.5, 0.1, dem::FrictionModel::history);
  bed::Bed b = sphere_over_groove();
  dem::SpreadSettings st = granular_run(1e-4, 0.0);
  st.floor = groove();
  st.floor.ny = 11;
  st.floor.z.resize(st.floor.nx * st.floor.ny);
  try {
    dem::run_spread(b, s, st);
    ADD_FAILURE() << "a floor spanning half the periodic y axis was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("periodic along y"), std::string::npos) << e.what();
  }
}

// Without damping or friction the floor's contacts conserve energy: each is the gradient of a
// potential (the exact distance to the triangles), so whenever the sphere is clear of the floor
// its kinetic plus gravitational energy per unit mass is the drop's start's, to within 0.2 % of
// the 8 um drop's over 20 ms of bouncing from slope to slope (measured: 0.02 %, velocity
// Verlet's error).
TEST(SpreadFloor, ElasticSphereBouncingInAGrooveKeepsItsEnergy) {
  dem::Scene s = granular_scene(0.0, 0.0, dem::FrictionModel::sliding);
  s.effects &= ~dem::kDamping;
  bed::Bed b = sphere_over_groove();
  dem::SpreadSettings st = granular_run(20e-3, 0.0);
  st.young_scale = 1e4;
  st.floor = groove();
  const double start = kG * b.z[0], drop = kG * (b.z[0] - 50e-6 - kRadius);
  double worst = 0;
  const bed::HeightMap floor = groove();
  st.observer = [&](std::uint64_t, double, const bed::Bed& bed, const std::vector<double>&) {
    if (bed::surface_overlap(floor, bed.x[0], bed.y[0], bed.z[0], kRadius) > 0) return false;  // in contact
    const double v2 = bed.vx[0] * bed.vx[0] + bed.vy[0] * bed.vy[0] + bed.vz[0] * bed.vz[0];
    worst = std::max(worst, std::abs(0.5 * v2 + kG * bed.z[0] - start));
    return false;
  };
  dem::run_spread(b, s, st);
  EXPECT_LT(worst, 2e-3 * drop);
  EXPECT_GT(std::abs(b.x[0] - 103e-6), 1e-6);  // it did move across the groove
}
