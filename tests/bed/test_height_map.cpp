// bed::HeightMap (the fused solid's top, spread on by dem and conducted through by thermal):
// bilinear between nodes and held beyond them, the nearest surface point of a sphere, and the
// seam of a periodic box.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "powderbed/bed/height_map.hpp"

using namespace powderbed;

namespace {

// 3 x 3 nodes 10 um apart; h = 1 um x i + 2 um x j (a plane: bilinear is exact on it).
bed::HeightMap plane() {
  bed::HeightMap m;
  m.nx = m.ny = 3;
  m.dx = m.dy = 10e-6;
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < 3; ++i) m.z.push_back(1e-6 * static_cast<double>(i) + 2e-6 * static_cast<double>(j));
  return m;
}

}  // namespace

TEST(HeightMap, BilinearOnAPlaneAndHeldBeyondTheGrid) {
  const bed::HeightMap m = plane();
  EXPECT_NEAR(m.at(5e-6, 15e-6), 0.5e-6 + 3e-6, 1e-18);
  const auto [sx, sy] = m.slope(5e-6, 15e-6);
  EXPECT_NEAR(sx, 0.1, 1e-12);
  EXPECT_NEAR(sy, 0.2, 1e-12);
  EXPECT_NEAR(m.at(-1e-3, -1e-3), 0.0, 1e-18);        // clamped onto the corner node
  EXPECT_NEAR(m.at(1e-3, 1e-3), 6e-6, 1e-18);
}

TEST(HeightMap, NearestPointAndOverlapOfASphere) {
  bed::HeightMap flat = plane();
  std::fill(flat.z.begin(), flat.z.end(), 0.0);
  // On a flat surface the nearest point is the foot: overlap r - z.
  EXPECT_NEAR(flat.overlap(10e-6, 10e-6, 4e-6, 5e-6), 1e-6, 1e-18);
  EXPECT_LE(flat.overlap(10e-6, 10e-6, 6e-6, 5e-6), 0.0);
  // A centre below the surface reaches r plus its depth into it.
  EXPECT_NEAR(flat.overlap(10e-6, 10e-6, -1e-6, 5e-6), 6e-6, 1e-18);
  // A step beside the foot is found: node (2, 1) raised 8 um, a sphere of 5 um at x = 15 um
  // resting 5.5 um above the floor touches the step's flank though the floor under it is clear.
  flat.z[2 + 3 * 1] = 8e-6;
  EXPECT_GT(flat.overlap(13e-6, 10e-6, 5.5e-6, 5e-6), 0.0);
}

TEST(HeightMap, PeriodicSeamKeepsTheVolume) {
  bed::HeightMap m = plane();
  const double before = std::accumulate(m.z.begin(), m.z.end(), 0.0);
  m.join_periodic_edges(false, true);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(m.node(i, 0), m.node(i, 2));
  EXPECT_NEAR(std::accumulate(m.z.begin(), m.z.end(), 0.0), before, 1e-20);
}
