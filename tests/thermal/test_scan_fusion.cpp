// Scan paths and fusion (issue 17, points 1 and 2): the single track is the one-segment path;
// hatches and CSV paths; per-track melt pools; fusion conserves mass, fuses a stripe as wide as
// the melt and leaves powder between tracks hatched too far apart; the solver runs on the raised
// top it leaves; a layer scanned twice fuses to itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/surface_contacts.hpp"
#include "powderbed/thermal/fusion.hpp"
#include "powderbed/thermal/lack_of_fusion.hpp"
#include "powderbed/thermal/scan_path.hpp"
#include "powderbed/thermal/solver.hpp"
#include "run_command.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;

namespace {

constexpr double kR = 8e-6;           // powder radius, m
constexpr double kSpacing = 1.98 * kR;  // lattice spacing: neighbours overlap by 1 % of r
constexpr double kDx = 4e-6;          // grid spacing, m
// 50 W at 1.5 m/s under a 20 µm spot melts two rows of this powder and the plate under them,
// vaporising none (at 80 W particles under the beam's axis vaporise): the melt is the powder's.
constexpr double kPower = 50;
// The ledger closes to round-off (test_energy_balance.cpp's bar).
constexpr double kBalance = 1e-6;

// One layer of equal spheres (radius kR) on the floor of a lx × ly plate: the thin powder layer
// of a track over a plate.
bed::Bed monolayer(double lx, double ly) {
  bed::Bed b = test::empty_bed(lx, ly, 6 * kR);
  const auto nx = static_cast<std::size_t>((lx - 2 * kR) / kSpacing) + 1;
  const auto ny = static_cast<std::size_t>((ly - 2 * kR) / kSpacing) + 1;
  const double x0 = 0.5 * (lx - static_cast<double>(nx - 1) * kSpacing);
  const double y0 = 0.5 * (ly - static_cast<double>(ny - 1) * kSpacing);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      b.add(x0 + static_cast<double>(i) * kSpacing, y0 + static_cast<double>(j) * kSpacing,
            test::resting_z(kR), kR);
  return b;
}

// [GZ]'s model (Beer–Lambert: deterministic and fast) on a grid of spacing kDx, 40 µm deep.
thermal::SinterScene scene_for(const bed::Bed& b) {
  const auto nodes = [&](double l) { return static_cast<std::size_t>(std::llround(l / kDx)) + 1; };
  auto scene = test::small_scene(thermal::kAllSinterEffects,
                                 {nodes(b.domain.length(0)), nodes(b.domain.length(1)), 11}, 40e-6);
  scene.power = kPower;
  scene.speed = 1.5;
  scene.spot_radius = 20e-6;
  return scene;
}

thermal::Hatch hatch_over(const bed::Bed& b, double spacing, std::size_t tracks) {
  thermal::Hatch h;
  h.spacing = spacing;
  h.tracks = tracks;
  h.direction = thermal::HatchDirection::one_way;
  const double margin = 20e-6;
  h.region = {margin, b.domain.length(0) - margin, margin, b.domain.length(1) - margin};
  h.power = kPower;
  h.speed = 1.5;
  return h;
}

struct Scanned {
  thermal::SinterResult result;
  thermal::Fusion fusion;
};

Scanned scan_and_fuse(const bed::Bed& b, const thermal::SinterScene& scene) {
  thermal::Sinter sinter(b, scene, test::table_316l());
  auto r = sinter.run(nullptr, 0, nullptr);
  return {r, thermal::fuse(b, sinter)};
}

// Top-face column heights above the plate along the grid line nearest x (i = round(x / dx)).
std::vector<double> raised_along_y(const thermal::Fusion& f, const thermal::SubstrateGeometry& g,
                                   double x) {
  const auto i = static_cast<std::size_t>(std::llround((x - g.x0) / g.dx));
  std::vector<double> out;
  for (std::size_t j = 0; j < g.ny; ++j) out.push_back(f.top[i + g.nx * j] - g.z_top);
  return out;
}

}  // namespace

// The single track of laser.* is the one-segment path from (start_x, y) to (end_x, y): a scene
// given that path explicitly runs the same steps bit for bit, with either laser model.
TEST(ScanPath, SingleTrackIsTheOneSegmentPath) {
  const bed::Bed b = monolayer(160e-6, 120e-6);
  for (const auto absorption : {thermal::LaserAbsorption::beer_lambert, thermal::LaserAbsorption::ray_trace}) {
    auto scene = scene_for(b);
    scene.absorption = absorption;
    scene.rays.rays = 400;
    scene.start_x = 10e-6;  // a path's ends lie on the plate
    scene.end_x = 150e-6;
    auto explicit_path = scene;
    const double y = 0.5 * b.domain.length(1);
    explicit_path.scan_path = {{10e-6, y, 150e-6, y, scene.power, scene.speed}};
    thermal::Sinter a(b, scene, test::table_316l()), c(b, explicit_path, test::table_316l());
    const auto ra = a.run(nullptr, 0, nullptr), rc = c.run(nullptr, 0, nullptr);
    EXPECT_EQ(ra.steps, rc.steps);
    EXPECT_EQ(ra.max_temperature, rc.max_temperature);
    EXPECT_EQ(ra.energy.absorbed(), rc.energy.absorbed());
    EXPECT_EQ(ra.melt_pool.width, rc.melt_pool.width);
    EXPECT_EQ(ra.melt_pool.depth, rc.melt_pool.depth);
    EXPECT_EQ(ra.absorptance, rc.absorptance);
    EXPECT_EQ(a.particle_max_temperature(), c.particle_max_temperature());
    ASSERT_EQ(ra.tracks.size(), 1u);
    EXPECT_GT(ra.tracks[0].pool.width, 0);
  }
}

// A hatch: N parallel tracks h apart centred on the region, clipped to it; alternating reverses
// every other one; layer k turns them by k × rotation about the region's centre.
TEST(ScanPath, HatchGeometry) {
  thermal::Hatch h;
  h.spacing = 50e-6;
  h.region = {0, 400e-6, 0, 200e-6};
  h.power = 100;
  h.speed = 1;
  h.rotation = 90;
  h.layer = 0;
  auto tracks = thermal::hatch_segments(h);  // fills the region: floor(200 / 50) + 1 = 5
  ASSERT_EQ(tracks.size(), 5u);
  for (std::size_t m = 0; m < tracks.size(); ++m) {
    EXPECT_NEAR(tracks[m].y0, static_cast<double>(m) * 50e-6, 1e-18);
    EXPECT_NEAR(tracks[m].length(), 400e-6, 1e-18);
    EXPECT_EQ(tracks[m].x0 < tracks[m].x1, m % 2 == 0) << "alternating";
  }
  h.layer = 1;  // 90°: along y, offsets along x
  tracks = thermal::hatch_segments(h);
  ASSERT_EQ(tracks.size(), 9u);  // 400 / 50 + 1
  EXPECT_NEAR(tracks[4].x0, 200e-6, 1e-15);
  EXPECT_NEAR(tracks[4].length(), 200e-6, 1e-15);
  h.rotation = 67;
  h.tracks = 3;
  tracks = thermal::hatch_segments(h);
  ASSERT_EQ(tracks.size(), 3u);
  const double angle = 67 * M_PI / 180;
  for (const auto& t : tracks) {  // along (cos 67°, sin 67°), ends on the region's boundary
    EXPECT_NEAR((t.x1 - t.x0) * std::sin(angle) - (t.y1 - t.y0) * std::cos(angle), 0, 1e-15);
    const auto on_edge = [](double x, double y) {
      return std::min({std::abs(x), std::abs(x - 400e-6), std::abs(y), std::abs(y - 200e-6)}) < 1e-15;
    };
    EXPECT_TRUE(on_edge(t.x0, t.y0) && on_edge(t.x1, t.y1));
  }
  h.spacing = 0;
  EXPECT_THROW(thermal::hatch_segments(h), InputError);
  h.spacing = 150e-6;
  h.tracks = 5;  // 600 µm of hatch across a 200 x 400 region at 67°: some lines miss it
  EXPECT_THROW(thermal::hatch_segments(h), InputError);
}

// The schedule: each segment runs length/speed; the laser is off for the jump, which takes its
// length over the jump speed.
TEST(ScanPath, ScheduleJumpsWithTheLaserOff) {
  const thermal::ScanSchedule path({{0, 0, 100e-6, 0, 50, 1}, {100e-6, 30e-6, 0, 30e-6, 80, 2}}, 3);
  EXPECT_DOUBLE_EQ(path.end(0), 100e-6);
  EXPECT_DOUBLE_EQ(path.start(1), 100e-6 + 30e-6 / 3);
  EXPECT_DOUBLE_EQ(path.finish(), path.start(1) + 50e-6);
  const auto mid_jump = path.at(105e-6);
  EXPECT_FALSE(mid_jump.on);
  EXPECT_EQ(mid_jump.power, 0);
  const auto second = path.at(path.start(1) + 10e-6);
  EXPECT_TRUE(second.on);
  EXPECT_EQ(second.segment, 1u);
  EXPECT_DOUBLE_EQ(second.x, 80e-6);
  EXPECT_DOUBLE_EQ(second.power, 80);
  EXPECT_FALSE(path.at(path.finish()).on);
  EXPECT_DOUBLE_EQ(path.beam_energy(1), 50 * 100e-6 + 80 * 50e-6);
}

// Bad paths are refused before anything runs: power < 0, speed <= 0, an end off the plate.
TEST(ScanPath, BadSegmentsRefused) {
  const bed::Bed b = monolayer(160e-6, 120e-6);
  const auto refused = [&](thermal::ScanSegment seg, const char* what) {
    auto scene = scene_for(b);
    scene.scan_path = {seg};
    try {
      thermal::Sinter s(b, scene, test::table_316l());
      ADD_FAILURE() << what << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused({20e-6, 60e-6, 140e-6, 60e-6, -1, 1}, "power");
  refused({20e-6, 60e-6, 140e-6, 60e-6, 50, 0}, "speed");
  refused({20e-6, 60e-6, 170e-6, 60e-6, 50, 1}, "leaves the plate");
  refused({20e-6, -1e-6, 140e-6, 60e-6, 50, 1}, "leaves the plate");
}

// A path read from CSV and the hatch it was written from are the same path: the same run.
TEST(ScanPath, CsvAndHatchGiveIdenticalResults) {
  const bed::Bed b = monolayer(240e-6, 200e-6);
  auto hatched = scene_for(b);
  auto h = hatch_over(b, 40e-6, 3);
  h.direction = thermal::HatchDirection::alternating;
  h.rotation = 67;
  h.layer = 1;
  hatched.scan_path = thermal::hatch_segments(h);
  const std::string csv = test::scratch_dir("scan_csv") + "/path.csv";
  std::ofstream(csv) << thermal::scan_csv(hatched.scan_path);
  auto read = scene_for(b);
  read.scan_path = thermal::read_scan_csv(csv);
  const auto a = scan_and_fuse(b, hatched), c = scan_and_fuse(b, read);
  ASSERT_EQ(a.result.tracks.size(), 3u);
  ASSERT_EQ(c.result.tracks.size(), 3u);
  for (std::size_t m = 0; m < 3; ++m) {
    const auto& ta = a.result.tracks[m];
    const auto& tc = c.result.tracks[m];
    EXPECT_EQ(ta.pool.width, tc.pool.width);
    EXPECT_EQ(ta.pool.depth, tc.pool.depth);
    EXPECT_EQ(ta.length, tc.length);
    EXPECT_EQ(ta.peak_temperature, tc.peak_temperature);
    EXPECT_EQ(ta.stored_energy, tc.stored_energy);
    EXPECT_GT(ta.pool.width, 0) << "track " << m << " melts";
  }
  EXPECT_EQ(a.fusion.top, c.fusion.top);
  EXPECT_LT(a.result.energy.relative_error(), kBalance);
}

// Two identical tracks far apart (mirror images on a symmetric bed and grid, 100 µm = 5 spot
// radii apart, the second starting on a plate the first warmed by ~10 K) melt the same pool:
// width and length within one grid cell (their resolution), depth within a quarter cell (an
// interpolated edge), peak temperature within 1 % (a 10 K preheat on a ~2700 K rise), molten
// particles within 15 % (the preheat tips edge particles that peak near T_m: 22 against 24).
TEST(ScanPath, IdenticalTracksFarApartAgree) {
  const bed::Bed b = monolayer(200e-6, 200e-6);
  auto scene = scene_for(b);
  scene.scan_path = {{20e-6, 50e-6, 180e-6, 50e-6, kPower, 1.5},
                     {20e-6, 150e-6, 180e-6, 150e-6, kPower, 1.5}};
  thermal::Sinter sinter(b, scene, test::table_316l());
  const auto r = sinter.run(nullptr, 0, nullptr);
  ASSERT_EQ(r.tracks.size(), 2u);
  const auto& one = r.tracks[0];
  const auto& two = r.tracks[1];
  EXPECT_GT(one.pool.width, 2 * kR);
  EXPECT_NEAR(one.pool.width, two.pool.width, kDx);
  EXPECT_NEAR(one.length, two.length, kDx);
  EXPECT_NEAR(one.pool.depth, two.pool.depth, kDx / 4);
  EXPECT_NEAR(one.peak_temperature, two.peak_temperature, 0.01 * one.peak_temperature);
  EXPECT_NEAR(static_cast<double>(one.particles_molten), static_cast<double>(two.particles_molten),
              0.15 * static_cast<double>(one.particles_molten));
  // What the first leaves for the second: heat stored, a warmer start.
  EXPECT_GT(one.stored_energy, 0);
  EXPECT_GT(two.start_temperature, one.start_temperature);
  EXPECT_DOUBLE_EQ(one.start_temperature, scene.initial_temperature);
  EXPECT_LT(r.energy.relative_error(), kBalance);
  std::printf("  width %.2f / %.2f um, depth %.3f / %.3f um, length %.1f / %.1f um, peak %.0f / "
              "%.0f K, molten %zu / %zu; second starts at %.1f K\n",
              one.pool.width * 1e6, two.pool.width * 1e6, one.pool.depth * 1e6,
              two.pool.depth * 1e6, one.length * 1e6, two.length * 1e6, one.peak_temperature,
              two.peak_temperature, one.particles_molten, two.particles_molten,
              two.start_temperature);
}

// Fusion moves mass from the powder to the solid and loses none: once on the flat plate, and
// again on the raised top the first left (a second scan on the powder that stayed).
TEST(Fusion, MassConserved) {
  const bed::Bed b = monolayer(240e-6, 200e-6);
  auto scene = scene_for(b);
  scene.scan_path = thermal::hatch_segments(hatch_over(b, 40e-6, 2));
  thermal::Sinter first(b, scene, test::table_316l());
  first.run(nullptr, 0, nullptr);
  const auto f1 = thermal::fuse(b, first);
  ASSERT_GT(f1.fused, 0u);
  EXPECT_EQ(f1.solid_mass_before, 0);
  const double removed = f1.powder_mass_before - f1.powder_mass_after - f1.vaporised_mass;
  EXPECT_NEAR(f1.solid_mass_after - f1.solid_mass_before, removed, 1e-12 * removed);
  EXPECT_LT(f1.mass_error(), 1e-12);
  EXPECT_EQ(f1.powder.n() + f1.fused + f1.vaporised, b.n());

  auto again = scene;
  again.scan_path = thermal::hatch_segments(hatch_over(b, 40e-6, 3));
  thermal::Sinter second(f1.powder, again, test::table_316l(), f1.top);
  const auto r = second.run(nullptr, 0, nullptr);
  EXPECT_LT(r.energy.relative_error(), kBalance);  // the raised top's kernel books every joule
  const auto f2 = thermal::fuse(f1.powder, second);
  ASSERT_GT(f2.fused, 0u);
  EXPECT_DOUBLE_EQ(f2.solid_mass_before, f1.solid_mass_after);
  EXPECT_LT(f2.mass_error(), 1e-12);
  std::printf("  fused %zu then %zu; mass error %.1e, %.1e; second run's balance %.1e\n", f1.fused,
              f2.fused, f1.mass_error(), f2.mass_error(), r.energy.relative_error());
}

// A single track over a plate with one layer of powder fuses a stripe (the columns the solid
// rose over, on the cross-section the melt pool is measured on) as wide as that melt pool, to
// within one grid cell: each column owns dy, so the stripe's extent is known to ±dy.
TEST(Fusion, SingleTrackFusesAStripeAsWideAsTheMelt) {
  const bed::Bed b = monolayer(240e-6, 160e-6);
  auto scene = scene_for(b);
  const double y = 0.5 * b.domain.length(1);
  scene.scan_path = {{20e-6, y, 220e-6, y, kPower, 1.5}};
  thermal::Sinter sinter(b, scene, test::table_316l());
  const auto r = sinter.run(nullptr, 0, nullptr);
  const auto f = thermal::fuse(b, sinter);
  const double melt = r.tracks.at(0).pool.width;
  ASSERT_GT(melt, 0);
  const auto raised = raised_along_y(f, sinter.grid(), 120e-6);
  std::size_t lo = raised.size(), hi = 0;
  for (std::size_t j = 0; j < raised.size(); ++j)
    if (raised[j] > 0) lo = std::min(lo, j), hi = std::max(hi, j);
  ASSERT_LE(lo, hi) << "nothing fused on the cross-section";
  const double dy = sinter.grid().dy;
  const double stripe = static_cast<double>(hi - lo + 1) * dy;
  EXPECT_NEAR(stripe, melt, dy) << "stripe " << stripe << " m, melt " << melt << " m";
  std::printf("  stripe %.2f um, melt width %.2f um (dy %.1f um); %zu fused, %zu powder\n",
              stripe * 1e6, melt * 1e6, dy * 1e6, f.fused, f.powder.n());
  // Unmelted particles stay powder: every particle the melt did not reach is in the bed left.
  EXPECT_EQ(f.powder.n() + f.fused, b.n());
  EXPECT_EQ(f.vaporised, 0u);
}

// Two tracks h apart: with h above twice the melt width powder is left unfused between them
// (lack of fusion); with h under half the melt width none is.
TEST(Fusion, HatchSpacingAndPowderLeftBetweenTracks) {
  const bed::Bed b = monolayer(240e-6, 200e-6);
  const auto between_unfused = [&](double spacing, double& width) {
    auto scene = scene_for(b);
    scene.scan_path = thermal::hatch_segments(hatch_over(b, spacing, 2));
    const auto s = scan_and_fuse(b, scene);
    width = std::max(s.result.tracks.at(0).pool.width, s.result.tracks.at(1).pool.width);
    const double y_lo = std::min(scene.scan_path[0].y0, scene.scan_path[1].y0);
    const double y_hi = std::max(scene.scan_path[0].y0, scene.scan_path[1].y0);
    std::size_t left = 0;
    for (std::size_t i = 0; i < b.n(); ++i) {
      // Between the centre lines, away from the tracks' ends (where the beam starts and stops).
      const bool between = b.y[i] > y_lo && b.y[i] < y_hi && b.x[i] > 60e-6 && b.x[i] < 180e-6;
      if (between && s.fusion.state[i] == 0) ++left;
    }
    return left;
  };
  double width_far = 0, width_near = 0;
  const std::size_t far = between_unfused(110e-6, width_far);
  const std::size_t near = between_unfused(16e-6, width_near);
  ASSERT_GT(width_far, 0);
  EXPECT_GT(110e-6, 2 * width_far) << "the far hatch is more than twice the melt width";
  EXPECT_LT(16e-6, 0.5 * width_near);
  EXPECT_GT(far, 0u);
  EXPECT_EQ(near, 0u);
  std::printf("  h 110 um, melt width %.2f um: %zu unfused between; h 16 um, width %.2f um: %zu\n",
              width_far * 1e6, far, width_near * 1e6, near);
}

// On a raised top the bed rests on the solid: a particle sitting on a 10 µm block fused there
// touches it (and is refused on the flat plate, where it floats), and a pass over it books
// every joule.
TEST(Fusion, SolverRunsOnTheRaisedTop) {
  bed::Bed b = test::empty_bed(120e-6, 120e-6, 60e-6);
  const double lift = 10e-6, r = 10e-6;
  b.add(60e-6, 60e-6, lift + test::resting_z(r), r);
  auto scene = scene_for(b);
  EXPECT_THROW(thermal::Sinter(b, scene, test::table_316l()), InputError);
  const std::size_t nx = scene.nodes[0], ny = scene.nodes[1];
  thermal::TopHeight top(nx * ny, 0.0);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const double x = static_cast<double>(i) * kDx, y = static_cast<double>(j) * kDx;
      if (std::abs(x - 60e-6) <= 30e-6 && std::abs(y - 60e-6) <= 30e-6) top[i + nx * j] = lift;
    }
  thermal::Sinter sinter(b, scene, test::table_316l(), top);
  ASSERT_EQ(sinter.network().substrate.size(), 1u);
  const auto run = sinter.run(nullptr, 0, nullptr);
  EXPECT_LT(run.energy.relative_error(), kBalance);
  EXPECT_GT(run.tracks.at(0).pool.width, 0);
  // Below the plate is refused.
  top[0] = -1e-6;
  EXPECT_THROW(thermal::Sinter(b, scene, test::table_316l(), top), InputError);
}

// A hatch over the whole plate (the default region of sinter) lies on it: its clipped ends are
// on the plate's edge exactly, at any rotation.
TEST(ScanPath, HatchOverTheWholePlateStaysOnIt) {
  const bed::Bed b = monolayer(160e-6, 120e-6);
  for (const std::size_t layer : {0u, 1u, 2u, 3u}) {
    auto scene = scene_for(b);
    thermal::Hatch h;
    h.spacing = 30e-6;
    h.layer = layer;
    h.region = {0, b.domain.length(0), 0, b.domain.length(1)};
    h.power = kPower;
    h.speed = 1.5;
    scene.scan_path = thermal::hatch_segments(h);
    EXPECT_NO_THROW(thermal::Sinter(b, scene, test::table_316l())) << "layer " << layer;
  }
}

// The per-track section works at any heading: on a bare plate (isotropic) a track at 45° melts
// the pool a track along x melts, width within one grid cell, depth within a quarter cell.
TEST(ScanPath, TrackHeadingDoesNotChangeItsPool) {
  const bed::Bed b = test::empty_bed(240e-6, 240e-6, 40e-6);
  const auto scene = scene_for(b);
  const double c = 120e-6, half = 80e-6, diag = half / std::sqrt(2.0);
  auto along_x = scene, oblique = scene;
  // 100 W: the bare plate takes the whole beam (no powder) and melts ~50 µm wide.
  along_x.scan_path = {{c - half, c, c + half, c, 100, 1.5}};
  oblique.scan_path = {{c - diag, c - diag, c + diag, c + diag, 100, 1.5}};
  thermal::Sinter a(b, along_x, test::table_316l()), o(b, oblique, test::table_316l());
  const auto ra = a.run(nullptr, 0, nullptr), ro = o.run(nullptr, 0, nullptr);
  const auto& ta = ra.tracks.at(0).pool;
  const auto& to = ro.tracks.at(0).pool;
  ASSERT_GT(ta.width, 2 * kDx);
  EXPECT_NEAR(to.width, ta.width, kDx);
  EXPECT_NEAR(to.depth, ta.depth, kDx / 4);
  std::printf("  along x: width %.2f um, depth %.2f um; at 45 deg: %.2f um, %.2f um\n",
              ta.width * 1e6, ta.depth * 1e6, to.width * 1e6, to.depth * 1e6);
}

// With capture (build), no powder particle left is buried in the grown solid deeper than the
// capture depth, the captured ones are counted among the fused, and mass is still conserved. On a
// grid as coarse as the build scene's (10 um, wider than these 8 um particles' footprints) a
// fused particle's volume goes to the four nodes around it and rises under its neighbours, which
// a capture of 0 leaves deep inside the solid. 60 W: at kPower this coarse grid's top face peaks
// at 1691 K, under T_m, so the molten particles meet no molten solid and ball (bonding.hpp).
TEST(Fusion, CaptureLeavesNoPowderBuriedInTheGrownSolid) {
  const bed::Bed b = monolayer(240e-6, 160e-6);
  auto scene = scene_for(b);
  scene.nodes = {25, 17, 5};
  const double y = 0.5 * b.domain.length(1);
  scene.scan_path = {{20e-6, y, 220e-6, y, 60, 1.5}};
  thermal::Sinter sinter(b, scene, test::table_316l());
  sinter.run(nullptr, 0, nullptr);
  const auto deepest = [&](const thermal::Fusion& f) {
    const bed::HeightMap top = thermal::top_surface(sinter.grid(), f.top);
    double worst = 0;
    for (std::size_t i = 0; i < b.n(); ++i)
      if (f.state[i] == 0) worst = std::max(worst, bed::surface_overlap(top, b.x[i], b.y[i], b.z[i], kR) / kR);
    return worst;
  };
  // The same depth found by brute force, the surface sampled at 61 x 61 points over the
  // footprint rather than the floor contact's 25: a spike a cell wide hides between those.
  const auto deepest_dense = [&](const thermal::Fusion& f) {
    const bed::HeightMap top = thermal::top_surface(sinter.grid(), f.top);
    double worst = 0;
    for (std::size_t i = 0; i < b.n(); ++i) {
      if (f.state[i] != 0) continue;
      double nearest = kR;
      for (int a = -30; a <= 30; ++a)
        for (int c = -30; c <= 30; ++c) {
          const double ex = kR * a / 30.0, ey = kR * c / 30.0;
          const double ez = top.at(b.x[i] + ex, b.y[i] + ey) - b.z[i];
          nearest = std::min(nearest, ez >= 0 ? -ez : std::sqrt(ex * ex + ey * ey + ez * ez));
        }
      worst = std::max(worst, (kR - nearest) / kR);
    }
    return worst;
  };
  const auto plain = thermal::fuse(b, sinter);
  const auto taken = thermal::fuse(b, sinter, 0.5, 0.05);
  ASSERT_GT(plain.fused, 0u);
  EXPECT_GT(deepest(plain), 0.05) << "the stripe's neighbours sit in the solid without capture";
  EXPECT_LE(deepest(taken), 0.05);
  EXPECT_GT(taken.captured, 0u);
  EXPECT_EQ(taken.fused, plain.fused + taken.captured);
  EXPECT_LT(taken.mass_error(), 1e-12);
  // Levelled over 10 um (build: half the beam radius) the deposit keeps its volume to round-off
  // and loses its spikes: the highest column is lower than where the particles fell.
  const auto level = thermal::fuse(b, sinter, 0.5, 0.0, 10e-6);
  EXPECT_LT(level.mass_error(), 1e-12);
  EXPECT_LT(*std::max_element(level.top.begin(), level.top.end()),
            0.8 * *std::max_element(plain.top.begin(), plain.top.end()));
  // Levelled, the captured particles' volume too: no spike is left that the 25 samples miss.
  const auto both = thermal::fuse(b, sinter, 0.5, 0.05, 10e-6);
  EXPECT_LE(deepest(both), 0.05);
  EXPECT_LE(deepest_dense(both), 0.06);
  EXPECT_LT(both.mass_error(), 1e-12);
  // ... and capture stays beside the melt: a captured particle touches the pool, the columns the
  // scan's levelled deposit reached (within 3 L + r of a fused particle), so it lies within
  // 3 L + 2 r (and a grid cell) of one; levelled everywhere, the tails ran capture through the bed.
  double farthest = 0;
  for (std::size_t i = 0; i < b.n(); ++i) {
    if (both.state[i] != 1 || plain.state[i] == 1) continue;
    double nearest = 1;
    for (std::size_t k = 0; k < b.n(); ++k)
      if (plain.state[k] == 1) nearest = std::min(nearest, std::hypot(b.x[i] - b.x[k], b.y[i] - b.y[k]));
    farthest = std::max(farthest, nearest);
  }
  EXPECT_LE(farthest, 3 * 10e-6 + 2 * kR + kDx);
  std::printf("  deepest powder in the solid: %.2f r without capture, %.3f r with (%zu fused, %zu "
              "captured); levelled too: %.3f r (%.3f r by brute force; %.3f r unlevelled), the farthest "
              "captured %.1f um from a fused one\n",
              deepest(plain), deepest(taken), plain.fused, taken.captured, deepest(both),
              deepest_dense(both), deepest_dense(taken), farthest * 1e6);
}

// On a y-periodic bed a track by the y = 0 edge raises that edge of the (non-periodic) grid
// and not the other: fuse makes the two edge rows one seam (their mean, mass kept) before it
// captures, so no powder resting by the low edge is left inside the joined step.
TEST(Fusion, PeriodicSeamIsJoinedBeforeTheCapture) {
  bed::Bed b = monolayer(240e-6, 160e-6);
  b.domain.periodic[1] = 1;
  auto scene = scene_for(b);
  // Along y = 16 um, not on the edge row itself: that row is Dirichlet (T0), and within 12 um of
  // it the plate stays under T_m at this power, so the molten particles there bond to nothing and
  // ball (bonding.hpp); the first row's footprints still reach the edge.
  scene.scan_path = {{20e-6, 16e-6, 220e-6, 16e-6, kPower, 1.5}};
  thermal::Sinter sinter(b, scene, test::table_316l());
  sinter.run(nullptr, 0, nullptr);
  const auto fused = thermal::fuse(b, sinter, 0.5, 0.05, 10e-6);
  const auto& g = sinter.grid();
  double step = 0, raised = 0;
  for (std::size_t i = 0; i < g.nx; ++i) {
    step = std::max(step, std::abs(fused.top[i] - fused.top[i + g.nx * (g.ny - 1)]));
    raised = std::max(raised, fused.top[i] - g.z_top);
  }
  ASSERT_GT(raised, 0.1 * kR) << "the track raises the seam; fused " << fused.fused << " balled " << fused.balled;
  EXPECT_EQ(step, 0.0);
  EXPECT_LT(fused.mass_error(), 1e-12);
  const bed::HeightMap top = thermal::top_surface(g, fused.top);
  for (std::size_t i = 0; i < b.n(); ++i) {
    if (fused.state[i] != 0) continue;
    EXPECT_LE(bed::surface_overlap(top, b.x[i], b.y[i], b.z[i], kR), 0.05 * kR) << i;
  }
}

// A layer scanned twice fuses to itself: the second pass, over the first one's fused top and the
// powder it left, remelts that deposit, so the columns the first pass bonded to the plate are
// bonded again, now to the first pass's solid (a melt reaching into the solid under it, at least
// one cell deep where the first pass bonded), and mass is kept through both fusions.
TEST(Fusion, LayerScannedTwiceFusesToItself) {
  const bed::Bed b = monolayer(240e-6, 200e-6);
  auto scene = scene_for(b);
  scene.scan_path = thermal::hatch_segments(hatch_over(b, 16e-6, 4));
  const double half_width = 8e-6, capture = 0.05, level = 10e-6;
  thermal::Sinter first(b, scene, test::table_316l());
  first.run(nullptr, 0, nullptr);
  const double t_m = first.material().phase_change().melting_point;
  const thermal::Fusion f1 = thermal::fuse(b, first, 0.5, capture, level);
  const thermal::LackOfFusion lof1 = thermal::lack_of_fusion(first, half_width, t_m);
  thermal::Sinter second(f1.powder, scene, test::table_316l(), f1.top);
  second.run(nullptr, 0, nullptr);
  const thermal::Fusion f2 = thermal::fuse(f1.powder, second, 0.5, capture, level);
  const thermal::LackOfFusion lof2 = thermal::lack_of_fusion(second, half_width, t_m, f1.top);
  EXPECT_LT(f1.mass_error(), 1e-12);
  EXPECT_LT(f2.mass_error(), 1e-12);
  ASSERT_GT(lof1.scanned, 0u);
  ASSERT_EQ(lof1.map.size(), lof2.map.size());
  std::size_t bonded = 0, again = 0, deep = 0, q = 0;
  for (std::size_t c = 0; c < lof2.map.size(); ++c) {
    if (lof2.map[c] == thermal::kNotScanned) continue;
    const double remelt = lof2.remelt[q++];
    if (lof1.map[c] != thermal::kBonded) continue;
    ++bonded;
    again += lof2.map[c] == thermal::kBonded ? 1 : 0;
    deep += remelt >= kDx ? 1 : 0;
  }
  ASSERT_GT(bonded, 0u);
  EXPECT_EQ(again, bonded) << "columns the first pass bonded that the second left unbonded";
  EXPECT_EQ(deep, bonded) << "columns the second pass remelted less than a cell deep";
  std::printf("  first pass: %zu of %zu scanned columns bonded, %zu fused; second: all %zu bonded "
              "again, remelt %.1f um mean; %zu fused\n",
              bonded, lof1.scanned, f1.fused, again, lof2.mean_remelt() * 1e6, f2.fused);
}

// The bead on the track's sections (bead.hpp): a ridge along x whose crest rises linearly from
// h0 to h1 over the grid's length, with a lower shoulder beside it. Each section's height is
// its crest (not the shoulder, not a mean across y), the plane x = Lx/2 the middle one, and
// over the steady part's sections (x_i for i in [nx/4, 3(nx-1)/4]) the mean and sd of n
// equally spaced values: the ends' mean and the discrete uniform's step √((n² − 1)/12).
// Nothing fused: a bead of height 0.
TEST(Bead, HeightIsEachSectionsCrestOverThePlate) {
  thermal::SubstrateGeometry g;
  g.nx = 41;
  g.ny = 9;
  g.nz = 5;
  g.dx = g.dy = g.dz = 5e-6;
  g.z_top = 1e-4;
  const double h0 = 10e-6, h1 = 30e-6;
  thermal::TopHeight top(g.columns(), g.z_top);
  const double span = static_cast<double>(g.nx - 1);
  const auto crest = [&](std::size_t i) { return h0 + (h1 - h0) * static_cast<double>(i) / span; };
  for (std::size_t i = 0; i < g.nx; ++i) {
    top[i + g.nx * 4] = g.z_top + crest(i);
    top[i + g.nx * 3] = top[i + g.nx * 5] = g.z_top + 0.5 * crest(i);
  }
  const thermal::Bead b = thermal::measure_bead(g, top);
  EXPECT_EQ(b.sections, 21u);  // i = 10 ... 30
  EXPECT_NEAR(b.height, crest(20), 1e-15);
  EXPECT_NEAR(b.height_mean, 0.5 * (crest(10) + crest(30)), 1e-15);
  const double n = 21, step = (h1 - h0) / span;
  EXPECT_NEAR(b.height_sd, step * std::sqrt((n * n - 1) / 12), 1e-12);
  const thermal::Bead none = thermal::measure_bead(g, {});
  EXPECT_EQ(none.height, 0.0);
  EXPECT_EQ(none.sections, 0u);
}
