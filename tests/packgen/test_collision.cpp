// Collision back-ends (docs/physics.md §3): the exact ones agree with brute force and with each other
// bit for bit; the raster grid errs only within its spacing.
#include <gtest/gtest.h>

#include <cmath>

#include "powderbed/bed/random.hpp"
#include "powderbed/packgen/cell_grid.hpp"
#include "powderbed/packgen/kdtree_index.hpp"
#include "powderbed/packgen/pack.hpp"
#include "powderbed/packgen/raster_grid.hpp"

namespace {

using namespace powderbed;
using namespace powderbed::packgen;
using bed::uniform;

bed::Domain box(int dim, double l) {
  bed::Domain d;
  d.dimension = dim;
  d.upper = {l, l, dim == 3 ? l : 0.0};
  return d;
}

bool brute_fits(const Particles& p, double x, double y, double z, double r,
                std::int64_t after = -1) {
  for (std::uint32_t j = static_cast<std::uint32_t>(after + 1); j < p.size(); ++j) {
    if (overlaps(p.x[j] - x, p.y[j] - y, p.z[j] - z, p.r[j] + r)) return false;
  }
  return true;
}

double deepest_overlap(const Particles& p, double x, double y, double z, double r) {
  double depth = 0;
  for (std::uint32_t j = 0; j < p.size(); ++j) {
    const double d = std::sqrt((p.x[j] - x) * (p.x[j] - x) + (p.y[j] - y) * (p.y[j] - y) +
                               (p.z[j] - z) * (p.z[j] - z));
    depth = std::max(depth, p.r[j] + r - d);
  }
  return depth;
}

void check_against_brute_force(int dim) {
  // Radii 0.01..0.1 (1:10, several grid levels) in a unit box; 60 disks or 300 spheres (about
  // half the space covered, so both answers are common), 3000 queries.
  const bed::Domain domain = box(dim, 1.0);
  const double r_min = 0.01, r_max = 0.1, h = 0.005;
  Particles p;
  CellGrid grid(domain, r_min, r_max, p);
  KdTreeIndex tree(dim, r_max, p);
  RasterGrid raster(domain, h, p);
  bed::Rng rng(7);
  auto coord = [&] { return uniform(rng, 0, 1); };
  const std::uint32_t count = dim == 2 ? 60 : 300;
  for (std::uint32_t i = 0; i < count; ++i) {
    p.x.push_back(coord());
    p.y.push_back(coord());
    p.z.push_back(dim == 3 ? coord() : 0.0);
    p.r.push_back(uniform(rng, r_min, r_max));
    grid.insert(i);
    tree.insert(i);
    raster.insert(i);
  }
  EXPECT_GT(grid.levels(), 1u);
  int collisions = 0;
  for (int q = 0; q < 3000; ++q) {
    const double x = coord(), y = coord(), z = dim == 3 ? coord() : 0.0;
    const double r = uniform(rng, r_min, r_max);
    const bool exact = brute_fits(p, x, y, z, r);
    EXPECT_EQ(grid.fits(x, y, z, r), exact);
    EXPECT_EQ(tree.fits(x, y, z, r), exact);
    // Only the particles after a given one (lowest-site growth re-tests a stored site so).
    const auto after = static_cast<std::int64_t>(uniform(rng, -1, count - 1));
    const bool newer = brute_fits(p, x, y, z, r, after);
    EXPECT_EQ(grid.fits(x, y, z, r, after), newer);
    EXPECT_EQ(tree.fits(x, y, z, r, after), newer);
    // Raster: a refusal means a grid point lies inside both, so the pair overlaps; an overlap
    // deeper than one grid cell diagonal (h sqrt(dim)) always contains a grid point.
    const bool raster_fits = raster.fits(x, y, z, r);
    if (!raster_fits) {
      EXPECT_FALSE(exact);
    }
    if (deepest_overlap(p, x, y, z, r) > h * std::sqrt(double(dim))) {
      EXPECT_FALSE(raster_fits);
    }
    collisions += !exact;
  }
  EXPECT_GT(collisions, 300);  // both answers are exercised
  EXPECT_LT(collisions, 2700);
}

TEST(Collision, AgreesWithBruteForce2D) { check_against_brute_force(2); }
TEST(Collision, AgreesWithBruteForce3D) { check_against_brute_force(3); }

TEST(Collision, TouchingIsAcceptedOverlapIsNot) {
  const bed::Domain domain = box(3, 1.0);
  Particles p{{0.5}, {0.5}, {0.5}, {0.1}};
  CellGrid grid(domain, 0.1, 0.1, p);
  KdTreeIndex tree(3, 0.1, p);
  grid.insert(0);
  tree.insert(0);
  // Touching at a distance that rounding puts 1e-15 relative short: accepted.
  EXPECT_TRUE(grid.fits(0.5 + 0.2 * (1 - 1e-15), 0.5, 0.5, 0.1));
  EXPECT_TRUE(tree.fits(0.5 + 0.2 * (1 - 1e-15), 0.5, 0.5, 0.1));
  // Overlapping by 1e-9 relative: refused.
  EXPECT_FALSE(grid.fits(0.5 + 0.2 * (1 - 1e-9), 0.5, 0.5, 0.1));
  EXPECT_FALSE(tree.fits(0.5 + 0.2 * (1 - 1e-9), 0.5, 0.5, 0.1));
}

// grid and kdtree consume the random stream identically and answer identically, so the beds
// are equal bit for bit (EXPECT_EQ on doubles, no tolerance).
void expect_same_beds(int dim, int approach, const std::string& psd_text) {
  const bed::Domain domain = box(dim, 12e-6);
  const bed::Psd psd = bed::Psd::parse(psd_text);
  PackOptions o;
  o.phases = {{approach, 1.0}};
  o.tries = 50;
  o.max_failures = 20;
  o.edge_fraction = 0.2;
  o.collision = Collision::grid;
  const PackResult a = pack(domain, psd, o, 99);
  o.collision = Collision::kdtree;
  const PackResult b = pack(domain, psd, o, 99);
  ASSERT_GT(a.bed.n(), 10u);
  ASSERT_EQ(a.bed.n(), b.bed.n());
  EXPECT_EQ(a.attempts, b.attempts);
  for (std::size_t i = 0; i < a.bed.n(); ++i) {
    EXPECT_EQ(a.bed.x[i], b.bed.x[i]);
    EXPECT_EQ(a.bed.y[i], b.bed.y[i]);
    EXPECT_EQ(a.bed.z[i], b.bed.z[i]);
    EXPECT_EQ(a.bed.radius[i], b.bed.radius[i]);
  }
}

TEST(Collision, GridAndKdTreeGiveTheSameBed) {
  const std::string wide = "gauss:mean=1e-6,sd=0.5e-6,min=0.2e-6,max=2e-6";
  for (int approach = 0; approach <= 2; ++approach) {
    SCOPED_TRACE(approach);
    expect_same_beds(2, approach, wide);
  }
  for (int approach = 0; approach <= 3; ++approach) {
    SCOPED_TRACE(approach);
    expect_same_beds(3, approach, wide);
  }
  // Monodisperse lowest-site growth re-tests stored sites against the newer particles only.
  expect_same_beds(3, 3, "mono:r=1e-6");
}

}  // namespace
