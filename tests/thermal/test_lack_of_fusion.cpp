// Lack of fusion (build, lack_of_fusion.hpp): a track over a bare plate bonds a stripe of the
// solid as wide as its melt; hatched tracks more than twice the melt width apart leave unbonded
// solid between them, tracks closer than half of it leave none; the never-molten solid a part
// keeps (part_porosity.hpp) loses what a later melt reaches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "powderbed/bed/errors.hpp"
#include "powderbed/thermal/fusion.hpp"
#include "powderbed/thermal/lack_of_fusion.hpp"
#include "powderbed/thermal/part_porosity.hpp"
#include "powderbed/thermal/scan_path.hpp"
#include "powderbed/thermal/solver.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;

namespace {

constexpr double kDx = 4e-6;     // grid spacing, m
constexpr double kPower = 50;    // W at 1.5 m/s under a 20 um spot: a melt of ~40 um on 316L
constexpr double kSpeed = 1.5;

// [GZ]'s model (Beer–Lambert: deterministic and fast) on a grid of spacing kDx, 40 um deep.
thermal::SinterScene scene_for(const bed::Bed& b) {
  const auto nodes = [&](double l) { return static_cast<std::size_t>(std::llround(l / kDx)) + 1; };
  auto scene = test::small_scene(thermal::kAllSinterEffects,
                                 {nodes(b.domain.length(0)), nodes(b.domain.length(1)), 11}, 40e-6);
  scene.power = kPower;
  scene.speed = kSpeed;
  scene.spot_radius = 20e-6;
  return scene;
}

struct Scan {
  thermal::SinterResult result;
  thermal::LackOfFusion lof;
  thermal::SubstrateGeometry grid;
};

Scan scan(const bed::Bed& b, const thermal::SinterScene& scene, double half_width) {
  thermal::Sinter sinter(b, scene, test::table_316l());
  Scan s{sinter.run(nullptr, 0, nullptr), {}, sinter.grid()};
  s.lof = thermal::lack_of_fusion(sinter, half_width,
                                  sinter.material().phase_change().melting_point);
  return s;
}

// A bare plate 240 x 160 um and one track along its middle.
bed::Bed bare_plate() { return test::empty_bed(240e-6, 160e-6, 40e-6); }
thermal::SinterScene one_track(const bed::Bed& b) {
  auto scene = scene_for(b);
  const double y = 0.5 * b.domain.length(1);
  scene.scan_path = {{20e-6, y, 220e-6, y, kPower, kSpeed}};
  return scene;
}

}  // namespace

// On a bare plate the melt is the solid's own: the bonded columns across the track's midpoint
// span its melt width to within one column (each owns dy, so the extent is known to +-dy).
TEST(LackOfFusion, TrackOverABarePlateBondsAStripeAsWideAsItsMelt) {
  const bed::Bed b = bare_plate();
  const auto scene = one_track(b);
  const Scan s = scan(b, scene, 60e-6);
  const double melt = s.result.tracks.at(0).pool.width;
  ASSERT_GT(melt, 0);
  const double stripe = thermal::bonded_width(s.lof, s.grid, 120e-6);
  EXPECT_NEAR(stripe, melt, s.grid.dy) << "stripe " << stripe << " m, melt " << melt << " m";
  // Scanned (within 60 um of the track) but outside the melt: unbonded.
  EXPECT_GT(s.lof.unbonded, 0u);
  std::printf("  stripe %.1f um, melt %.1f um (dy %.1f um); lack of fusion %.3f\n", stripe * 1e6,
              melt * 1e6, s.grid.dy * 1e6, s.lof.fraction());
}

// The remelt depth is the melt's depth into the solid: on a bare plate the deepest column's is
// the track's pool depth on its mid section (both interpolate the same peaks to T_m; the section
// is one plane, the columns all of them, so the deepest column lies within a cell of it), the
// columns outside the melt have none, and over a plate raised by a block the depth counts from
// the block's top, not the plate's.
TEST(LackOfFusion, RemeltDepthIsTheMeltsDepthBelowTheSolidsTop) {
  const bed::Bed b = bare_plate();
  const auto scene = one_track(b);
  const Scan s = scan(b, scene, 60e-6);
  const double depth = s.result.tracks.at(0).pool.depth;
  ASSERT_GT(depth, 2 * kDx);
  ASSERT_EQ(s.lof.remelt.size(), s.lof.scanned);
  const double deepest = *std::max_element(s.lof.remelt.begin(), s.lof.remelt.end());
  EXPECT_NEAR(deepest, depth, kDx);
  EXPECT_EQ(s.lof.min_remelt(), 0.0) << "scanned columns outside the melt";
  std::size_t shallow = 0;
  for (const double d : s.lof.remelt) shallow += d == 0 ? 1 : 0;
  EXPECT_EQ(shallow, s.lof.unbonded);
  // The whole plate raised 3 cells is a plate 3 cells deeper: the same track remelts what it
  // remelts there, counted from the raised top (GrowingGrid.WholePlanesRaisedConductAsTheDeeperPlate).
  const double lift = 3 * kDx;
  thermal::SinterScene deeper = scene;
  deeper.nodes[2] += 3;
  deeper.substrate_depth += lift;
  const Scan d = scan(b, deeper, 60e-6);
  const thermal::TopHeight top(scene.nodes[0] * scene.nodes[1], lift);
  thermal::Sinter raised(b, scene, test::table_316l(), top);
  raised.run(nullptr, 0, nullptr);
  const auto lof = thermal::lack_of_fusion(raised, 60e-6,
                                           raised.material().phase_change().melting_point, top);
  ASSERT_EQ(lof.remelt.size(), d.lof.remelt.size());
  for (std::size_t q = 0; q < lof.remelt.size(); ++q) EXPECT_NEAR(lof.remelt[q], d.lof.remelt[q], 1e-12);
  std::printf("  pool depth %.2f um; deepest remelt %.2f um, mean %.2f um; on the raised plate "
              "mean %.2f um (the deeper plate's %.2f um)\n",
              depth * 1e6, deepest * 1e6, s.lof.mean_remelt() * 1e6, lof.mean_remelt() * 1e6,
              d.lof.mean_remelt() * 1e6);
}

// Two tracks h apart, each answering for a strip h wide: h above twice the melt width leaves the
// solid between them unbonded; h under half of it bonds the whole strip away from the tracks'
// ends (where the beam starts and stops, within one spot radius).
TEST(LackOfFusion, HatchSpacingDecidesLackOfFusionBetweenTracks) {
  const bed::Bed b = test::empty_bed(240e-6, 240e-6, 40e-6);
  const auto unbonded_between = [&](double spacing, double& width, double& fraction) {
    auto scene = scene_for(b);
    thermal::Hatch h;
    h.spacing = spacing;
    h.tracks = 2;
    h.direction = thermal::HatchDirection::one_way;
    h.region = {20e-6, 220e-6, 20e-6, 220e-6};
    h.power = kPower;
    h.speed = kSpeed;
    scene.scan_path = thermal::hatch_segments(h);
    const Scan s = scan(b, scene, 0.5 * spacing);
    width = std::max(s.result.tracks.at(0).pool.width, s.result.tracks.at(1).pool.width);
    fraction = s.lof.fraction();
    std::size_t left = 0;
    for (std::size_t j = 0; j < s.grid.ny; ++j)
      for (std::size_t i = 0; i < s.grid.nx; ++i) {
        const double x = s.grid.x(i);
        if (x < 60e-6 || x > 180e-6) continue;
        left += s.lof.map[i + s.grid.nx * j] == thermal::kUnbonded ? 1 : 0;
      }
    return left;
  };
  double far_width = 0, near_width = 0, far_fraction = 0, near_fraction = 0;
  const std::size_t far = unbonded_between(110e-6, far_width, far_fraction);
  const std::size_t near = unbonded_between(16e-6, near_width, near_fraction);
  ASSERT_GT(far_width, 0);
  EXPECT_GT(110e-6, 2 * far_width);
  EXPECT_LT(16e-6, 0.5 * near_width);
  EXPECT_GT(far, 0u);
  EXPECT_GT(far_fraction, 0.2);
  EXPECT_EQ(near, 0u);
  std::printf("  h 110 um, melt %.1f um: %zu unbonded columns (fraction %.3f); h 16 um, melt %.1f "
              "um: %zu (fraction %.3f)\n", far_width * 1e6, far, far_fraction, near_width * 1e6,
              near, near_fraction);
}

// A half width that is not a positive length is refused, naming what it is.
TEST(LackOfFusion, BadHalfWidthRefused) {
  const bed::Bed b = test::empty_bed(120e-6, 120e-6, 40e-6);
  auto scene = scene_for(b);
  thermal::Sinter sinter(b, scene, test::table_316l());
  EXPECT_THROW(thermal::lack_of_fusion(sinter, 0.0, 1700), InputError);
}

// A scene without a scan path runs its single track from the [GZ] defaults (laser.y, start and end
// x left NaN); the mask must come from that track as run, not from the scene's NaNs (issue 32: a
// single-track build counted nothing as scanned).
TEST(LackOfFusion, SingleTrackOfTheDefaultsIsScanned) {
  const bed::Bed b = test::empty_bed(240e-6, 160e-6, 40e-6);
  const thermal::SinterScene scene = scene_for(b);
  ASSERT_TRUE(scene.scan_path.empty());
  ASSERT_TRUE(std::isnan(scene.laser_y));
  const Scan s = scan(b, scene, scene.spot_radius);
  // The strip of half width w along the whole plate (the track starts and ends a spot beyond
  // it): 2w / dy + 1 rows of nx columns, to one row.
  const double rows = static_cast<double>(s.lof.scanned) / static_cast<double>(s.grid.nx);
  EXPECT_NEAR(rows, 2 * scene.spot_radius / s.grid.dy + 1, 1.0);
  EXPECT_GT(s.lof.scanned - s.lof.unbonded, 0u);  // the melt bonded to the plate under it
}

namespace {

// The plate raised by `lift` of captured powder (never molten: the record of one layer that
// scanned every column) and one track over it: the track's lack of fusion, its fusion and the
// record before this layer.
struct BlockUnderTrack {
  thermal::LackOfFusion lof;
  thermal::Fusion fusion;
  thermal::PartRecord record;
};
BlockUnderTrack block_under_track(thermal::Sinter& raised, const bed::Bed& b,
                                  const thermal::TopHeight& top, double lift) {
  raised.run(nullptr, 0, nullptr);
  const double t_m = raised.material().phase_change().melting_point;
  BlockUnderTrack s{thermal::lack_of_fusion(raised, 60e-6, t_m, top), thermal::fuse(b, raised),
                    thermal::part_record(raised.grid())};
  const thermal::SubstrateGeometry& g = raised.grid();
  s.record.layers = 1;
  for (std::size_t c = 0; c < g.columns(); ++c) {
    s.record.top[c] = top[c];
    s.record.scanned[c] = 1;
    s.record.never_molten[c] = {{g.z_top, g.z_top + lift}};
  }
  return s;
}

}  // namespace

// The part's porosity (part_porosity.hpp): a layer's melt takes the never-molten solid under it
// down to the melt's bottom, column by column. The plate raised by a block of captured powder
// (never molten, 3 cells thick) and one track over it: what is left in each scanned column is
// the block less that column's remelt depth (lack_of_fusion's own), the porosity is that over
// the block, and the cells of the field hold the same volumes.
TEST(PartPorosity, MeltTakesTheNeverMoltenSolidDownToItsBottom) {
  const bed::Bed b = bare_plate();
  const double lift = 3 * kDx;
  const auto scene = one_track(b);
  const thermal::TopHeight top(scene.nodes[0] * scene.nodes[1], lift);
  thermal::Sinter raised(b, scene, test::table_316l(), top);
  auto [lof, f, r] = block_under_track(raised, b, top, lift);
  const thermal::SubstrateGeometry& g = raised.grid();
  // Powder this layer's fusion captured over column 0, far from the track.
  f.top[0] += 5e-6;
  thermal::record_layer(r, raised, f, lof);
  ASSERT_EQ(r.never_molten[0].size(), 2u);
  EXPECT_EQ(r.never_molten[0][1].lo, f.melt_top[0]);
  EXPECT_EQ(r.never_molten[0][1].hi, f.top[0]);
  double left = 0, held = 0;
  std::size_t q = 0, emptied = 0;
  for (std::size_t c = 0; c < g.columns(); ++c) {
    if (lof.map[c] == thermal::kNotScanned) continue;
    const double expected = std::max(0.0, lift - lof.remelt[q++]);
    double kept = 0;
    for (const auto& s : r.never_molten[c]) kept += s.hi - s.lo;
    EXPECT_NEAR(kept, expected, 1e-15) << "column " << c;
    emptied += kept == 0 ? 1 : 0;
    left += expected;
    held += lift;
  }
  EXPECT_GT(emptied, 0u) << "the track remelts more than the block under its middle";
  const thermal::PartPorosity p = thermal::part_porosity(r);
  EXPECT_EQ(p.core_columns, lof.scanned);
  EXPECT_NEAR(p.fraction(), left / held, 1e-12);
  const thermal::PartField field = thermal::part_field(r);
  double cells = 0, intervals = 0;
  for (const double v : field.never_molten) cells += v * g.dz;
  for (const auto& column : r.never_molten)
    for (const auto& s : column) intervals += s.hi - s.lo;
  EXPECT_NEAR(cells, intervals, 1e-12 * intervals);
  std::printf("  block %.0f um: porosity of the scanned columns %.3f after the track; %zu of %zu "
              "columns remelted through\n",
              lift * 1e6, p.fraction(), emptied, lof.scanned);
}

// The interior (part_porosity.hpp): below the top the layer before the last left. Powder the
// last layer's fusion captured on top of its melt over every column counts in the whole part's
// porosity and not in the interior's, which is the block's remainder under the track alone.
TEST(PartPorosity, InteriorLeavesOutTheFilmTheLastLayerCaptured) {
  const bed::Bed b = bare_plate();
  const double lift = 3 * kDx, film = 5e-6;
  const auto scene = one_track(b);
  const thermal::TopHeight top(scene.nodes[0] * scene.nodes[1], lift);
  thermal::Sinter raised(b, scene, test::table_316l(), top);
  auto [lof, f, r] = block_under_track(raised, b, top, lift);
  const thermal::SubstrateGeometry& g = raised.grid();
  for (std::size_t c = 0; c < g.columns(); ++c) f.top[c] = f.melt_top[c] + film;
  const thermal::PartPorosity before = thermal::part_porosity(r);
  thermal::record_layer(r, raised, f, lof);
  const thermal::PartPorosity whole = thermal::part_porosity(r), inside = thermal::interior_porosity(r);
  double left = 0, films = 0, under = 0;
  for (std::size_t c = 0; c < g.columns(); ++c) {
    if (lof.map[c] == thermal::kNotScanned) continue;
    for (const auto& s : r.never_molten[c]) left += std::max(0.0, std::min(s.hi, r.below_last[c]) - s.lo);
    films += f.top[c] - std::max(f.melt_top[c], r.below_last[c]);
    under += r.below_last[c] - g.z_top;
  }
  const double area = g.dx * g.dy;
  EXPECT_EQ(inside.core_columns, lof.scanned);
  EXPECT_NEAR(inside.volume, area * under, 1e-12 * inside.volume);
  EXPECT_NEAR(inside.never_molten, area * left, 1e-12 * inside.volume);
  EXPECT_LT(inside.never_molten, before.never_molten) << "the track remelted some of the block";
  EXPECT_NEAR(whole.never_molten - inside.never_molten, area * films, 1e-12 * whole.volume);
  EXPECT_GT(whole.fraction(), inside.fraction());
  // After one layer there is no interior yet.
  thermal::PartRecord first = thermal::part_record(g);
  thermal::record_layer(first, raised, f, lof);
  EXPECT_EQ(thermal::interior_porosity(first).volume, 0.0);
  EXPECT_GT(thermal::part_porosity(first).volume, 0.0);
  std::printf("  film %.0f um over a %.0f um block: porosity %.3f of the whole part, %.3f of its "
              "interior\n", film * 1e6, lift * 1e6, whole.fraction(), inside.fraction());
}
