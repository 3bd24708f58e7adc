// The small laws bed/ holds for every stage (one equation, one file), each checked against the
// equation written out here independently and against a property it must have.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "powderbed/bed/sphere_volume.hpp"

namespace pb = powderbed::bed;

TEST(SphereVolume, IsFourThirdsPiRCubedAndFillsPiOverSixOfItsCube) {
  // 4/3 pi = 4.18879020478639... (the unit sphere); 1e-15 relative is a few ulp.
  EXPECT_NEAR(pb::sphere_volume(1.0), 4.1887902047863905, 1e-15 * 4.19);
  // A sphere fills pi/6 of the cube it is inscribed in, at any size (1e-14: a few roundings).
  for (const double r : {1e-6, 27e-6, 0.5e-3}) {
    EXPECT_NEAR(pb::sphere_volume(r) / (8 * r * r * r), std::numbers::pi / 6, 1e-14);
  }
}
