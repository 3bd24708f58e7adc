// Energy conservation, initial overlaps, non-finite runs, determinism across thread counts,
// input checks and trajectory output of the deposition solver (issue 4 "hard cases").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "beds.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_input.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/time_step.hpp"
#include "powderbed/dem/trajectory.hpp"

using namespace powderbed;

namespace {

// 40 particles, r in [10, 20] um, random positions and speeds up to 0.2 m/s in a 0.3 mm box.
bed::Bed gas_bed(std::uint64_t seed) {
  bed::Bed b = test::box_bed(0.3e-3, 0.3e-3, 0.3e-3);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.3e-3, 0.3e-3, 0.3e-3};
  test::add_random(b, 40, 10e-6, 20e-6, lo, hi, seed);
  bed::Rng rng(seed + 1);
  for (std::size_t i = 0; i < b.n(); ++i) {
    b.vx.push_back(bed::uniform(rng, -0.2, 0.2));
    b.vy.push_back(bed::uniform(rng, -0.2, 0.2));
    b.vz.push_back(bed::uniform(rng, -0.2, 0.2));
  }
  return b;
}

}  // namespace

class EnergyConservation : public ::testing::TestWithParam<dem::Integrator> {};

TEST_P(EnergyConservation, ElasticBoxConservesEnergy) {
  bed::Bed b = gas_bed(7);
  const dem::Scene scene = test::scene_with(dem::kGravity | dem::kHertz | dem::kWalls);
  const double e0 = dem::energy(b, scene).total();
  dem::RunSettings s;
  s.integrator = GetParam();
  s.young_scale = 1e3;  // softened: t_R is then ~3.5e-7 s and 3e5 steps cover 2 ms
  s.dt = 0.02 * dem::time_step_bound(b, scene, s.young_scale).stable;
  s.t_end = 2e-3;  // every particle crosses the box a few times: hundreds of collisions
  std::size_t contacts_seen = 0;
  s.observe_every = 100;
  s.observer = [&](std::uint64_t, double, const bed::Bed& bb) {
    contacts_seen += dem::energy(bb, scene, s.young_scale).elastic > 0;
    return false;
  };
  dem::run_deposition(b, scene, s);
  EXPECT_GT(contacts_seen, 10u);  // the test exercises contacts, not only free flight
  const double e1 = dem::energy(b, scene, s.young_scale).total();
  // Issue 4: 1e-6 relative. Verlet's energy error is bounded by ~(omega dt)^2 of the contact
  // energy (omega dt <= 0.02 here; at 0.05 t_R it measured 3e-6) and RK4's drift is O(dt^4).
  EXPECT_NEAR(e1, e0, 1e-6 * e0);
}

INSTANTIATE_TEST_SUITE_P(Integrators, EnergyConservation,
                         ::testing::Values(dem::Integrator::verlet, dem::Integrator::rk4));

TEST(Robustness, TwentyPercentOverlapsDoNotExplode) {
  // 4x4x3 simple-cubic block of 20 um spheres at spacing 1.8 r: every neighbour pair overlaps
  // by 0.2 r, and the bottom layer overlaps the floor by 0.1 r.
  const double r = 20e-6, a = 1.8 * r;
  bed::Bed b = test::box_bed(0.3e-3, 0.3e-3, 0.3e-3);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) b.add(0.1e-3 + i * a, 0.1e-3 + j * a, 0.9 * r + k * a, r);
  const dem::Scene scene;  // every effect of the paper's scene, full E
  const double e0 = dem::energy(b, scene).total();
  const double m = test::sphere_mass(r, scene.material.density);
  // Damping, friction and drag only remove energy, so no particle can be faster than if it
  // took all of it (stored elastic + gravitational) alone.
  const double v_bound = std::sqrt(2 * e0 / m);
  dem::RunSettings s;
  // The released particles reach ~350 m/s (measured) and cross the 0.1 mm to the walls in
  // ~100 of the 2000 steps, so the walls take full-speed hits too.
  s.t_end = 2000 * dem::time_step_bound(b, scene, 1).recommended;
  double v_max = 0, ke_max = 0;
  std::size_t outside = 0;  // particle-steps with a centre outside the box
  s.observer = [&](std::uint64_t, double, const bed::Bed& bb) {
    for (std::size_t i = 0; i < bb.n(); ++i) v_max = std::max(v_max, std::hypot(bb.vx[i], bb.vy[i], bb.vz[i]));
    ke_max = std::max(ke_max, dem::energy(bb, scene).kinetic);
    for (std::size_t i = 0; i < bb.n(); ++i) {
      outside += bb.x[i] < 0 || bb.x[i] > 0.3e-3 || bb.y[i] < 0 || bb.y[i] > 0.3e-3 ||
                 bb.z[i] < 0 || bb.z[i] > 0.3e-3;
    }
    return false;
  };
  const auto summary = dem::run_deposition(b, scene, s);
  EXPECT_LE(v_max, v_bound);
  EXPECT_LE(ke_max, e0);  // bounded kinetic energy, at every step
  EXPECT_EQ(outside, 0u);  // no particle leaves the box at any step, not only at the end
  EXPECT_EQ(summary.lost, 0u);
  EXPECT_LT(dem::energy(b, scene).total(), e0);  // damped: energy went down, not up
}

TEST(Robustness, NonFiniteRunNamesParticleAndStep) {
  // 20 % overlaps with --unsafe-dt at 50 t_R: the pair flies apart into the walls, each wall
  // contact overshoots deeper than the last and the explicit step diverges.
  const double r = 20e-6;
  bed::Bed b = test::box_bed(0.3e-3, 0.3e-3, 0.3e-3);
  b.add(1.5e-4, 1.5e-4, 1.5e-4, r);
  b.add(1.5e-4 + 1.8 * r, 1.5e-4, 1.5e-4, r);
  const dem::Scene scene = test::scene_with(dem::kHertz | dem::kWalls);
  dem::RunSettings s;
  s.dt = 50 * dem::time_step_bound(b, scene, 1).stable;
  s.unsafe_dt = true;
  s.t_end = 1e4 * s.dt;
  try {
    dem::run_deposition(b, scene, s);
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("particle id"), std::string::npos) << what;
    EXPECT_NE(what.find("step"), std::string::npos) << what;
  }
}

TEST(Robustness, DtAboveBoundIsRefusedUnlessUnsafe) {
  bed::Bed b = test::box_bed(0.3e-3, 0.3e-3, 0.3e-3);
  b.add(1.5e-4, 1.5e-4, 1.5e-4, 20e-6);
  const dem::Scene scene;
  dem::RunSettings s;
  s.dt = 1.5 * dem::time_step_bound(b, scene, 1).stable;
  s.t_end = 10 * s.dt;
  EXPECT_THROW(dem::run_deposition(b, scene, s), InputError);
  s.unsafe_dt = true;
  EXPECT_NO_THROW(dem::run_deposition(b, scene, s));
}

TEST(Robustness, ParticleOutsideDomainIsRefused) {
  bed::Bed b = test::box_bed(0.3e-3, 0.3e-3, 0.3e-3);
  b.add(1.5e-4, 1.5e-4, 0.4e-3, 20e-6);
  dem::RunSettings s;
  s.t_end = 1e-6;
  EXPECT_THROW(dem::run_deposition(b, dem::Scene{}, s), InputError);
}

TEST(Determinism, OneAndTwoThreadsGiveBitIdenticalBeds) {
  // 300 particles moving at up to 0.2 m/s in a periodic-x box with every effect on: ~2000
  // Verlet steps (or 500 RK4 steps) with many collisions, on 1 and on 2 threads.
  for (auto integrator : {dem::Integrator::verlet, dem::Integrator::rk4}) {
    bed::Bed start = test::box_bed(0.4e-3, 0.3e-3, 0.4e-3);
    start.domain.periodic[0] = true;
    const double lo[3] = {0, 0, 0}, hi[3] = {0.4e-3, 0.3e-3, 0.4e-3};
    test::add_random(start, 300, 10e-6, 20e-6, lo, hi, 11);
    bed::Rng rng(12);
    for (std::size_t i = 0; i < start.n(); ++i) {
      start.vx.push_back(bed::uniform(rng, -0.2, 0.2));
      start.vy.push_back(bed::uniform(rng, -0.2, 0.2));
      start.vz.push_back(bed::uniform(rng, -0.2, 0.2));
    }
    dem::RunSettings s;
    s.integrator = integrator;
    s.young_scale = 1e3;
    s.t_end = integrator == dem::Integrator::verlet ? 1.5e-4 : 3.5e-5;
    s.parallel_min_particles = 0;  // 300 particles: below the default, force the parallel path
    bed::Bed one = start, two = start;
    s.threads = 1;
    const auto summary = dem::run_deposition(one, dem::Scene{}, s);
    s.threads = 2;
    dem::run_deposition(two, dem::Scene{}, s);
    EXPECT_GT(summary.neighbour_rebuilds, 0u);
    // Bit-identical, not close: forces are summed per particle in a fixed order.
    EXPECT_EQ(one.x, two.x);
    EXPECT_EQ(one.y, two.y);
    EXPECT_EQ(one.z, two.z);
    EXPECT_EQ(one.vz, two.vz);
  }
}

TEST(Trajectory, WritesTimeSeriesAndXdmfCollection) {
  bed::Bed b = test::box_bed(0.3e-3, 0.3e-3, 0.3e-3);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.3e-3, 0.3e-3, 0.3e-3};
  test::add_random(b, 20, 10e-6, 20e-6, lo, hi, 5);
  const std::string path = "/tmp/powderbed_dem_traj_" + std::to_string(::getpid()) + ".h5";
  dem::RunSettings s;
  s.young_scale = 1e3;
  s.dt = 1e-7;
  s.t_end = 100 * s.dt;
  s.trajectory = path;
  s.trajectory_every = 25;
  dem::run_deposition(b, dem::Scene{}, s);
  std::ifstream h5(path, std::ios::binary);
  EXPECT_TRUE(h5.good());
  const std::string xmf = path.substr(0, path.size() - 3) + ".xmf";
  std::ifstream in(xmf);
  std::stringstream text;
  text << in.rdbuf();
  const std::string x = text.str();
  EXPECT_NE(x.find("CollectionType=\"Temporal\""), std::string::npos);
  std::size_t grids = 0;
  for (auto p = x.find("<Time "); p != std::string::npos; p = x.find("<Time ", p + 1)) ++grids;
  EXPECT_EQ(grids, 5u);  // steps 0, 25, 50, 75, 100
  std::remove(path.c_str());
  std::remove(xmf.c_str());
}

// The XDMF names a dataset only where the file has it: a snapshot of a bed without velocities
// (bedconv's dumps without vx vy vz) gets no velocity attribute, a later one with them does.
TEST(Trajectory, XdmfNamesOnlyDatasetsThatExist) {
  bed::Bed b = test::box_bed(0.3e-3, 0.3e-3, 0.3e-3);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.3e-3, 0.3e-3, 0.3e-3};
  test::add_random(b, 5, 10e-6, 20e-6, lo, hi, 3);
  ASSERT_FALSE(b.has_velocity());
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("powderbed_dem_traj_xdmf_" + std::to_string(::getpid()) + ".h5"))
                               .string();
  dem::TrajectoryWriter writer(path, b);
  writer.write(0, 0.0, b);
  b.vx.assign(b.n(), 1.0);
  b.vy.assign(b.n(), 0.0);
  b.vz.assign(b.n(), -1.0);
  writer.write(10, 1e-6, b);
  writer.close();
  const std::string xmf = path.substr(0, path.size() - 3) + ".xmf";
  std::ifstream in(xmf);
  std::stringstream text;
  text << in.rdbuf();
  const std::string x = text.str();
  const bed::H5Input h5(path);
  const std::string file = path.substr(path.rfind('/') + 1) + ":";
  std::size_t items = 0;
  for (auto p = x.find(file); p != std::string::npos; p = x.find(file, p + 1), ++items) {
    const std::size_t begin = p + file.size();
    const std::string dataset = x.substr(begin, x.find('<', begin) - begin);
    EXPECT_TRUE(h5.exists(dataset)) << dataset;
  }
  EXPECT_EQ(items, 2u * 3u + 1u);  // topology, position, radius per grid; velocity in the second
  const auto velocity = x.find("Name=\"velocity\"");
  EXPECT_GT(velocity, x.find("step 10\""));
  EXPECT_EQ(x.find("Name=\"velocity\"", velocity + 1), std::string::npos);
  std::remove(path.c_str());
  std::remove(xmf.c_str());
}
