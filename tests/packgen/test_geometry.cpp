// Closed-form contact positions (docs/physics.md §3 2-contact and 3-contact) and their hard cases.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "powderbed/bed/random.hpp"
#include "powderbed/packgen/contact_geometry.hpp"

namespace {

using namespace powderbed::packgen;
using powderbed::bed::Rng;
using powderbed::bed::uniform;

// Contacts must hold to 1e-12 relative: the closed forms lose a few ulps (~1e-15) in good
// cases and at most ~kClampTolerance / 2 = 5e-13 when a near-tangent discriminant is clamped.
constexpr double kTouch = 1e-12;

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

Partner ball(double x, double y, double z, double r) { return Partner::particle({x, y, z}, r); }

TEST(ContactGeometry, TwoContact2DTouchesBothOnRandomPairs) {
  Rng rng(11);
  int solved = 0;
  for (int k = 0; k < 2000; ++k) {
    const double r = uniform(rng, 0.1, 1.0);  // size ratios up to 1:10
    const Partner a = ball(uniform(rng, -1, 1), uniform(rng, -1, 1), 0, uniform(rng, 0.1, 1));
    const Partner b = ball(uniform(rng, -1, 1), uniform(rng, -1, 1), 0, uniform(rng, 0.1, 1));
    std::array<Vec3, 2> x;
    const int m = touch_two_2d(a, b, r, x);
    for (int s = 0; s < m; ++s) {
      ASSERT_TRUE(finite(x[s]));
      EXPECT_LE(contact_residual(a, x[s], r), kTouch);
      EXPECT_LE(contact_residual(b, x[s], r), kTouch);
      EXPECT_EQ(x[s].z, 0.0);
    }
    solved += m > 0;
  }
  EXPECT_GT(solved, 500);  // most random pairs are in reach: the test exercises solutions
}

TEST(ContactGeometry, TwoContact2DNearTangentAndDegenerate) {
  const double r = 1.0;
  std::array<Vec3, 2> x;
  // Exactly tangent (discriminant 0): both solutions are the one tangent point.
  const Partner a = ball(0, 0, 0, 1), b = ball(4, 0, 0, 1);
  ASSERT_EQ(touch_two_2d(a, b, r, x), 2);
  for (const Vec3& p : x) {
    EXPECT_NEAR(p.x, 2.0, 1e-12);
    EXPECT_NEAR(p.y, 0.0, 1e-6);  // sqrt of a rounding-size discriminant
    EXPECT_LE(contact_residual(a, p, r), kTouch);
    EXPECT_LE(contact_residual(b, p, r), kTouch);
  }
  // Beyond tangent by 1e-14 relative: clamped, still touching within tolerance, no NaN.
  const Partner b2 = ball(4 * (1 + 1e-14), 0, 0, 1);
  const int m = touch_two_2d(a, b2, r, x);
  for (int s = 0; s < m; ++s) {
    ASSERT_TRUE(finite(x[s]));
    EXPECT_LE(contact_residual(b2, x[s], r), kTouch);
  }
  // Clearly out of reach, and coincident centres: no solution.
  EXPECT_EQ(touch_two_2d(a, ball(4.001, 0, 0, 1), r, x), 0);
  EXPECT_EQ(touch_two_2d(a, ball(0, 0, 0, 0.5), r, x), 0);
}

TEST(ContactGeometry, TwoContact2DWithWall) {
  // A particle of radius 1 at height 1.5 above the floor y = 0; the new particle (r = 0.5)
  // touches it and the floor: centre at y = 0.5.
  const Partner a = ball(0, 1.5, 0, 1), floor = Partner::plane({0, 1, 0}, 0.0);
  std::array<Vec3, 2> x;
  ASSERT_EQ(touch_two_2d(a, floor, 0.5, x), 2);
  for (const Vec3& p : x) {
    EXPECT_NEAR(p.y, 0.5, 1e-15);
    EXPECT_LE(contact_residual(a, p, 0.5), kTouch);
  }
}

TEST(ContactGeometry, CircleOfTwoContactIn3D) {
  Rng rng(12);
  for (int k = 0; k < 500; ++k) {
    const double r = uniform(rng, 0.1, 1.0);
    const Partner a = ball(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), 1.0);
    const Partner b = ball(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), 0.1);
    Circle c;
    if (!touch_two_3d(a, b, r, c)) continue;
    for (double angle = 0; angle < 6.3; angle += 0.7) {
      const Vec3 p = c.at(angle);
      ASSERT_TRUE(finite(p));
      EXPECT_LE(contact_residual(a, p, r), kTouch);
      EXPECT_LE(contact_residual(b, p, r), kTouch);
    }
  }
}

TEST(ContactGeometry, TrilaterationTouchesAllThree) {
  Rng rng(13);
  int solved = 0;
  for (int k = 0; k < 2000; ++k) {
    const double r = uniform(rng, 0.1, 1.0);
    Partner p[3];
    for (auto& q : p) {
      q = ball(uniform(rng, -1.5, 1.5), uniform(rng, -1.5, 1.5), uniform(rng, -1.5, 1.5),
               uniform(rng, 0.1, 1.0));
    }
    std::array<Vec3, 2> x;
    const int m = touch_three_3d(p[0], p[1], p[2], r, x);
    for (int s = 0; s < m; ++s) {
      ASSERT_TRUE(finite(x[s]));
      for (const auto& q : p) EXPECT_LE(contact_residual(q, x[s], r), kTouch);
    }
    solved += m == 2;
  }
  EXPECT_GT(solved, 200);
}

TEST(ContactGeometry, TrilaterationHardCases) {
  std::array<Vec3, 2> x;
  // Colinear centres: the solutions form a circle, not two points -> no solution, no NaN.
  EXPECT_EQ(touch_three_3d(ball(0, 0, 0, 1), ball(2, 0, 0, 1), ball(4, 0, 0, 1), 1.0, x), 0);
  EXPECT_EQ(touch_three_3d(ball(0, 0, 0, 1), ball(2, 0, 0, 1), ball(4, 1e-13, 0, 1), 1.0, x), 0);
  // Three touching unit spheres in a triangle: the new unit sphere sits on top (tetrahedron),
  // near-tangent when it is exactly in reach.
  const double s3 = std::sqrt(3.0);
  const Partner t[3] = {ball(0, 0, 0, 1), ball(2, 0, 0, 1), ball(1, s3, 0, 1)};
  ASSERT_EQ(touch_three_3d(t[0], t[1], t[2], 1.0, x), 2);
  for (const Vec3& p : x) {
    EXPECT_NEAR(std::abs(p.z), 2 * std::sqrt(2.0 / 3.0), 1e-14);
    for (const auto& q : t) EXPECT_LE(contact_residual(q, p, 1.0), kTouch);
  }
  // The radius that fits exactly into the triangle's plane (discriminant 0): r = 2/sqrt3 - 1.
  const double r0 = 2 / s3 - 1;
  const int m = touch_three_3d(t[0], t[1], t[2], r0, x);
  for (int s = 0; s < m; ++s) {
    ASSERT_TRUE(finite(x[s]));
    for (const auto& q : t) EXPECT_LE(contact_residual(q, x[s], r0), kTouch);
  }
  // Size ratio 1:10 and a particle in a corner: one sphere, two walls.
  const Partner big = ball(0.8, 0.8, 2, 1);
  const Partner wx = Partner::plane({1, 0, 0}, 0.0), wy = Partner::plane({0, 1, 0}, 0.0);
  ASSERT_EQ(touch_three_3d(big, wx, wy, 0.1, x), 2);
  for (const Vec3& p : x) {
    EXPECT_NEAR(p.x, 0.1, 1e-15);
    EXPECT_NEAR(p.y, 0.1, 1e-15);
    EXPECT_LE(contact_residual(big, p, 0.1), kTouch);
  }
  // Parallel walls cannot both be touched: no solution.
  EXPECT_EQ(touch_three_3d(big, wx, Partner::plane({-1, 0, 0}, -2.0), 0.1, x), 0);
}

}  // namespace
