// libprocess's plan and layer measures against their definitions: the hatch of layer k turned
// k - 1 steps past the first layer's, the tool's height, the refusals of check_layers, and the
// scanned layer density of spheres placed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/process/build_plan.hpp"
#include "powderbed/process/scanned_layer_density.hpp"

namespace pr = powderbed::process;
namespace th = powderbed::thermal;
using powderbed::InputError;

namespace {

pr::BuildPlan hatched_plan() {
  pr::BuildPlan p;
  th::Hatch h;
  h.spacing = 100e-6;
  h.rotation = 67;
  h.layer = 3;  // the scene's scan.layer: the first layer's step
  h.region = {0, 1e-3, 0, 1e-3};
  h.power = 200;
  h.speed = 1;
  p.hatch = h;
  p.scan.scan_path = th::hatch_segments(h);
  p.spread.tool.gap = 90e-6;
  p.spread.layer_thickness = 45e-6;
  p.finest_diameter = 15e-6;
  return p;
}

powderbed::bed::Domain box(double height) {
  powderbed::bed::Domain d;
  d.upper = {1e-3, 1e-3, height};
  return d;
}

}  // namespace

TEST(BuildPlan, LayerKScansTheHatchTurnedKMinusOneStepsPastTheFirst) {
  const pr::BuildPlan p = hatched_plan();
  for (std::uint64_t k : {1u, 2u, 5u}) {
    th::Hatch h = *p.hatch;
    h.layer = 3 + k - 1;
    const auto expected = th::hatch_segments(h);
    const auto got = pr::scan_for_layer(p, k).scan_path;
    ASSERT_EQ(got.size(), expected.size()) << k;
    for (std::size_t m = 0; m < got.size(); ++m) {
      EXPECT_EQ(got[m].x0, expected[m].x0) << k;
      EXPECT_EQ(got[m].y1, expected[m].y1) << k;
    }
  }
  // Layer 2's first track runs at 4 x 67 degrees from +x.
  const auto s = pr::scan_for_layer(p, 2).scan_path.front();
  const double angle = std::atan2(s.y1 - s.y0, s.x1 - s.x0) * 180 / std::numbers::pi;
  EXPECT_NEAR(std::remainder(angle - 4 * 67.0, 180.0), 0.0, 1e-9);
}

TEST(BuildPlan, WithoutAHatchEveryLayerScansTheSamePath) {
  pr::BuildPlan p = hatched_plan();
  p.hatch.reset();
  EXPECT_EQ(pr::scan_for_layer(p, 7).scan_path.size(), p.scan.scan_path.size());
  EXPECT_EQ(pr::scan_for_layer(p, 7).scan_path.front().x0, p.scan.scan_path.front().x0);
  p.scan.spot_radius = 40e-6;
  EXPECT_EQ(pr::scanned_half_width(p), 40e-6);
  EXPECT_EQ(pr::scanned_half_width(hatched_plan()), 50e-6);
}

TEST(BuildPlan, ToolRisesOneLayerThicknessALayerAndChecksRefuse) {
  const pr::BuildPlan p = hatched_plan();
  EXPECT_DOUBLE_EQ(pr::tool_bottom(p, box(1e-3), 1), 90e-6);
  EXPECT_DOUBLE_EQ(pr::tool_bottom(p, box(1e-3), 3), 180e-6);
  // Tool bottoms 90, 135, ..., 90 + 45 (N - 1) um under a 300 um box: 5 layers fit.
  EXPECT_NO_THROW(pr::check_layers(p, box(300e-6), 1, 5));
  try {
    pr::check_layers(p, box(300e-6), 1, 6);
    FAIL() << "6 layers under a 300 um box";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at most 5 layers"), std::string::npos) << e.what();
  }
  pr::BuildPlan thin = p;
  thin.spread.layer_thickness = 10e-6;
  EXPECT_THROW(pr::check_layers(thin, box(1e-3), 1, 2), InputError);
  EXPECT_NO_THROW(pr::check_layers(thin, box(1e-3), 1, 1));  // the first layer is the gap
}

TEST(ScannedLayerDensity, SpheresOverScannedColumnsOverTheSpaceUnderTheTool) {
  th::SubstrateGeometry g;
  g.nx = g.ny = 3;
  g.nz = 2;
  g.dx = g.dy = g.dz = 10e-6;
  th::LackOfFusion lof;
  lof.map.assign(9, th::kNotScanned);
  lof.map[4] = th::kBonded;  // only the middle column (node 1, 1 at x = y = 10 um) was scanned
  powderbed::bed::Bed bed;
  const double r = 2e-6;
  const auto add = [&](double x, double y, double z) {
    bed.x.push_back(x);
    bed.y.push_back(y);
    bed.z.push_back(z);
    bed.radius.push_back(r);
    bed.id.push_back(bed.id.size());
  };
  add(10e-6, 10e-6, 5e-6);   // counted
  add(12e-6, 9e-6, 20e-6);   // counted: its column is the middle one
  add(0, 0, 5e-6);           // over an unscanned column
  add(10e-6, 10e-6, 31e-6);  // above the tool's bottom
  const double bottom = 30e-6;
  const double sphere = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(pr::scanned_layer_density(bed, g, {}, lof, bottom), 2 * sphere / (g.dx * g.dy * bottom),
              1e-12);
  // On a raised top the space is from the column's own top.
  const th::TopHeight top(9, 10e-6);
  EXPECT_NEAR(pr::scanned_layer_density(bed, g, top, lof, bottom),
              2 * sphere / (g.dx * g.dy * (bottom - 10e-6)), 1e-12);
  lof.map[4] = th::kNotScanned;
  EXPECT_EQ(pr::scanned_layer_density(bed, g, {}, lof, bottom), 0.0);
}
