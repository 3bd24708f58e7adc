// build's process-map criteria (apps/build_map.hpp), point by point against their definitions:
// King's normalised enthalpy or W/D <= 1.5 (keyhole), the part's porosity >= 1 % (lack of
// fusion), a free melt longer than pi W (balling), Tang's sum in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "build_map.hpp"

using powderbed::app::MapPoint;

namespace {

// 200 W, 1 m/s, 100 um hatch, 45 um layer, a pool 120 um wide and 60 um deep, nothing wrong.
MapPoint dense_point() {
  MapPoint p;
  p.power = 200;
  p.speed = 1;
  p.hatch = 100e-6;
  p.layer = 45e-6;
  p.width = 120e-6;
  p.depth = 60e-6;
  p.normalised_enthalpy = 3;
  p.keyhole_threshold = 5.8;
  p.porosity = 0.002;
  return p;
}

std::vector<std::string> regions(const MapPoint& p) { return p.regions(); }

}  // namespace

TEST(BuildMap, EachCriterionDecidesItsRegion) {
  EXPECT_EQ(regions(dense_point()), std::vector<std::string>{"dense"});
  MapPoint hot = dense_point();
  hot.normalised_enthalpy = 6;
  EXPECT_EQ(regions(hot), std::vector<std::string>{"keyhole"});
  MapPoint deep = dense_point();
  deep.depth = 80e-6;  // W/D = 1.5
  EXPECT_EQ(regions(deep), std::vector<std::string>{"keyhole"});
  deep.depth = 79e-6;
  EXPECT_EQ(regions(deep), std::vector<std::string>{"dense"});
  MapPoint porous = dense_point();
  porous.porosity = powderbed::app::kDensePorosity;
  EXPECT_EQ(regions(porous), std::vector<std::string>{"lack of fusion"});
  porous.balling_tracks = 1;
  EXPECT_EQ(regions(porous), (std::vector<std::string>{"lack of fusion", "balling"}));
}

TEST(BuildMap, EnergyDensityAndTangsSum) {
  const MapPoint p = dense_point();
  EXPECT_NEAR(p.energy_density(), 200 / (1 * 100e-6 * 45e-6), 1e-6);  // 44.4 J/mm^3
  const double h = 100.0 / 120, t = 45.0 / (45 + 60);
  EXPECT_NEAR(p.tang(), h * h + t * t, 1e-12);
  MapPoint none = p;
  none.depth = 0;  // nothing bonds: the sum is unbounded
  EXPECT_TRUE(std::isinf(none.tang()));
}
