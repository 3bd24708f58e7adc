// The small laws bed/ holds for every stage (one equation, one file), each checked against the
// equation written out here independently and against a property it must have.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "powderbed/bed/critical_damping.hpp"
#include "powderbed/bed/radiative_exchange.hpp"
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

TEST(RadiativeExchange, IsSigmaGDifferenceOfFourthPowersWithItsSlope) {
  const double g = 3e-7, hot = 1000, cold = 300;  // m^2, K
  const double q = pb::radiative_exchange(g, hot, cold);
  // sigma G (T_a^4 - T_b^4) written out; 1e-14 relative: a few roundings.
  EXPECT_NEAR(q, 5.670374419e-8 * g * (std::pow(hot, 4) - std::pow(cold, 4)), 1e-14 * q);
  EXPECT_EQ(pb::radiative_exchange(g, cold, cold), 0.0);
  EXPECT_EQ(pb::radiative_exchange(g, cold, hot), -q);
  // The slope by central differences (step 1e-3 K: truncation ~1e-9 relative, 1e-6 is far above
  // it and far below a wrong power).
  const double h = 1e-3;
  const double slope = (pb::radiative_exchange(g, hot + h, cold) - pb::radiative_exchange(g, hot - h, cold)) / (2 * h);
  EXPECT_NEAR(pb::radiative_conductance(g, hot), slope, 1e-6 * slope);
}
