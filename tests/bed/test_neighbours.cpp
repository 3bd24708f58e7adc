// Neighbour search (docs/physics.md §2): cell list, kd-tree and brute force agree exactly with each other
// and with an independent minimum-image reference written here, on random polydisperse beds.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/neighbours.hpp"
#include "powderbed/bed/random.hpp"

namespace pb = powderbed::bed;

namespace {

struct Case {
  const char* name;
  int dimension;
  std::array<double, 3> size;
  std::array<bool, 3> periodic;
  double gap;
  std::uint64_t seed;
  double outside;  // fraction of the box length that centres may reach beyond the box
};

// Radii uniform in [0.5, 1.5] (a 3:1 size ratio), centres uniform in the box widened by
// `outside` on every side (so wrapping and the cell list's extent are both exercised).
pb::Bed random_bed(const Case& c, std::size_t n) {
  pb::Bed bed;
  bed.domain.dimension = c.dimension;
  bed.domain.upper = c.size;
  if (c.dimension == 2) bed.domain.upper[2] = 0;
  bed.domain.periodic = c.periodic;
  pb::Rng rng(c.seed);
  bed.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<double, 3> p{0, 0, 0};
    for (int a = 0; a < c.dimension; ++a) {
      const double w = c.outside * c.size[a];
      p[a] = pb::uniform(rng, -w, c.size[a] + w);
    }
    bed.add(p[0], p[1], p[2], pb::uniform(rng, 0.5, 1.5));
  }
  return bed;
}

struct RefPair {
  std::uint32_t i, j;
  double distance;
};

// Independent reference: every pair, minimum image by std::remainder (result in [-L/2, L/2]).
std::vector<RefPair> reference(const pb::Bed& bed, double gap, double cutoff) {
  std::vector<RefPair> out;
  const std::vector<double>* c[3] = {&bed.x, &bed.y, &bed.z};
  for (std::uint32_t i = 0; i < bed.n(); ++i) {
    for (std::uint32_t j = i + 1; j < bed.n(); ++j) {
      double d2 = 0;
      for (int a = 0; a < bed.domain.dimension; ++a) {
        double d = (*c[a])[j] - (*c[a])[i];
        if (bed.domain.periodic[a]) d = std::remainder(d, bed.domain.length(a));
        d2 += d * d;
      }
      const double d = std::sqrt(d2);
      const double limit = cutoff > 0 ? cutoff : bed.radius[i] + bed.radius[j] + gap;
      if (d <= limit) out.push_back({i, j, d});
    }
  }
  return out;
}

void expect_identical(const std::vector<pb::NeighbourPair>& a,
                      const std::vector<pb::NeighbourPair>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].i, b[k].i) << what << " pair " << k;
    ASSERT_EQ(a[k].j, b[k].j) << what << " pair " << k;
    // Same geometry code on the same wrapped centres: bit-identical distances.
    ASSERT_EQ(a[k].distance, b[k].distance) << what << " pair " << k;
  }
}

void expect_matches_reference(const std::vector<pb::NeighbourPair>& got,
                              const std::vector<RefPair>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 0; k < got.size(); ++k) {
    ASSERT_EQ(got[k].i, want[k].i) << "pair " << k;
    ASSERT_EQ(got[k].j, want[k].j) << "pair " << k;
    // Wrapping centres into the box first vs std::remainder of the raw difference: both exact
    // up to a few roundings of coordinates of size ~100, so ~1e-13 absolute on distances ~3.
    EXPECT_NEAR(got[k].distance, want[k].distance, 1e-11) << "pair " << k;
  }
}

class NeighbourSearch : public ::testing::TestWithParam<Case> {};

// 3000 particles per bed: enough for thousands of pairs and every cell-adjacency case, small
// enough for the O(N^2) references to run in well under a second.
TEST_P(NeighbourSearch, CellListKdTreeAndBruteForceAgree) {
  const Case& c = GetParam();
  const pb::Bed bed = random_bed(c, 3000);
  const auto brute = pb::neighbour_pairs_brute_force(bed, c.gap);
  const auto cells = pb::neighbour_pairs_cell_list(bed, c.gap);
  const auto tree = pb::neighbour_pairs_kdtree(bed, c.gap);
  EXPECT_GT(brute.size(), 1000u) << "the bed should have many pairs to compare";
  expect_identical(cells, brute, "cell list vs brute force");
  expect_identical(tree, brute, "kd-tree vs brute force");
  expect_matches_reference(cells, reference(bed, c.gap, 0));
}

TEST_P(NeighbourSearch, PairsWithinCutoffMatchReference) {
  const Case& c = GetParam();
  const pb::Bed bed = random_bed(c, 3000);
  const double cutoff = 2.5;  // about the neighbour search radius, independent of the radii
  expect_matches_reference(pb::pairs_within_cell_list(bed, cutoff), reference(bed, 0, cutoff));
}

// Boxes: 3D 30^3 (3000 spheres of mean radius 1 overlap freely: ~10 neighbours each), 2D 100^2.
// Thin periodic axes (length 5 < 3 cells of the 3.2 cutoff, and < 2 cutoffs) use the fallback
// that visits every cell of the axis; pairs are then listed once at the minimum image.
INSTANTIATE_TEST_SUITE_P(
    RandomBeds, NeighbourSearch,
    ::testing::Values(
        Case{"box3d", 3, {30, 30, 30}, {false, false, false}, 0.2, 11, 0.0},
        Case{"periodic_xy", 3, {30, 30, 30}, {true, true, false}, 0.2, 12, 0.05},
        Case{"periodic_all", 3, {30, 30, 30}, {true, true, true}, 0.2, 13, 0.05},
        Case{"thin_periodic_z", 3, {60, 60, 5}, {true, false, true}, 0.2, 14, 0.02},
        Case{"outside_box", 3, {30, 30, 30}, {false, false, false}, 0.0, 15, 0.2},
        Case{"overlap_only", 3, {20, 20, 20}, {true, false, false}, -0.5, 16, 0.0},
        Case{"disks", 2, {100, 100, 0}, {false, false, false}, 0.2, 17, 0.0},
        Case{"disks_periodic", 2, {100, 100, 0}, {true, true, false}, 0.2, 18, 0.05},
        Case{"disks_thin_periodic", 2, {300, 4, 0}, {false, true, false}, 0.1, 19, 0.0}),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

TEST(NeighbourSearch, SmallBeds) {
  pb::Bed bed;
  EXPECT_TRUE(pb::neighbour_pairs_cell_list(bed, 0.1).empty());
  EXPECT_TRUE(pb::neighbour_pairs_kdtree(bed, 0.1).empty());
  bed.add(0.5, 0.5, 0.5, 0.1);
  EXPECT_TRUE(pb::neighbour_pairs_cell_list(bed, 0.1).empty());
  bed.add(0.5, 0.5, 0.75, 0.1);  // gap 0.05
  EXPECT_EQ(pb::neighbour_pairs_cell_list(bed, 0.1).size(), 1u);
  EXPECT_EQ(pb::neighbour_pairs_kdtree(bed, 0.1).size(), 1u);
  EXPECT_TRUE(pb::neighbour_pairs_cell_list(bed, 0.01).empty());
}

TEST(NeighbourSearch, PeriodicPairAcrossTheFace) {
  pb::Bed bed;
  bed.domain.periodic = {true, false, false};
  bed.add(0.02, 0.5, 0.5, 0.05);
  bed.add(0.97, 0.5, 0.5, 0.05);  // 0.05 apart through the x face
  for (const auto& pairs : {pb::neighbour_pairs_cell_list(bed, 0.0),
                            pb::neighbour_pairs_kdtree(bed, 0.0),
                            pb::neighbour_pairs_brute_force(bed, 0.0)}) {
    ASSERT_EQ(pairs.size(), 1u);
    // Coordinates 0.02 and 0.97 carry ~1e-17 rounding; the difference loses nothing more.
    EXPECT_NEAR(pairs[0].distance, 0.05, 1e-15);
  }
}

TEST(NeighbourSearch, RejectsBadInput) {
  pb::Bed bed;
  bed.add(0.5, 0.5, 0.5, 0.1);
  bed.add(0.6, 0.5, 0.5, 0.1);
  EXPECT_THROW(pb::neighbour_pairs_cell_list(bed, std::nan("")), powderbed::InputError);
  EXPECT_THROW(pb::neighbour_pairs_kdtree(bed, std::numeric_limits<double>::infinity()),
               powderbed::InputError);
  EXPECT_THROW(pb::pairs_within_cell_list(bed, 0.0), powderbed::InputError);
  bed.x[1] = std::nan("");
  EXPECT_THROW(pb::neighbour_pairs_cell_list(bed, 0.1), powderbed::InputError);
}

}  // namespace
