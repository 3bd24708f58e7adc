// The small laws bed/ holds for every stage (one equation, one file), each checked against the
// equation written out here independently and against a property it must have.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "powderbed/bed/critical_damping.hpp"
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

TEST(CriticalDamping, IsTwoZetaSqrtMkAndCriticalAtZetaOne) {
  const double m = 2e-9, k = 3e4;  // kg, N/m
  EXPECT_DOUBLE_EQ(pb::critical_damping(0.1, m, k), 2 * 0.1 * std::sqrt(m * k));
  // At zeta = 1 the characteristic roots of m x'' + c x' + k x = 0 coincide: c^2 = 4 m k
  // (1e-12 relative: two roundings of c squared, far below a factor error).
  const double c = pb::critical_damping(1.0, m, k);
  EXPECT_NEAR(c * c, 4 * m * k, 1e-12 * 4 * m * k);
  EXPECT_EQ(pb::critical_damping(0.0, m, k), 0.0);
}
