// Spread-layer statistics (docs/spread-layer.md) against closed forms: a square-lattice
// monolayer (density, coverage, mean height, Sa, Sq), plane cuts of a sphere (spherical caps),
// the segregation slope of a bed whose size grows linearly along x, and the KS test.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/bed/stats_layer.hpp"

namespace pb = powderbed::bed;
using std::numbers::pi;

namespace {

// n x n equal spheres of radius r resting on the plate z = 0 at spacing 2r (touching), in a
// 2rn x 2rn x 4r box periodic in y (as a spread strip) and walled in x.
pb::Bed square_monolayer(int n, double r) {
  pb::Bed bed;
  bed.domain.lower = {0, 0, 0};
  bed.domain.upper = {2 * r * n, 2 * r * n, 4 * r};
  bed.domain.periodic = {false, true, false};
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) bed.add(2 * r * (i + 0.5), 2 * r * (j + 0.5), r, r);
  }
  return bed;
}

pb::LayerRequest request(const pb::Bed& bed, double gap, double raster) {
  pb::LayerRequest q;
  q.plate = bed.domain.lower[2];
  q.gap = gap;
  q.x0 = bed.domain.lower[0];
  q.x1 = bed.domain.upper[0];
  q.raster = raster;
  return q;
}

double cap_volume(double r, double h) { return pi * h * h * (3 * r - h) / 3; }

}  // namespace

// ----------------------------------------------------------------------------- monolayer

TEST(SpreadLayer, SquareMonolayerMatchesClosedForms) {
  const double r = 10e-6;
  const int n = 6;
  const pb::Bed bed = square_monolayer(n, r);
  // raster r/50: the worst case for sampling (the lattice aligned with the raster) leaves
  // 0.08 % in coverage, 0.05 % in the mean height, 0.17 % in Sa and 0.10 % in Sq (midpoint sums
  // of one unit cell against the integrals below, computed once with numpy); tolerance 0.5 %.
  pb::LayerRequest q = request(bed, 2 * r, r / 50);
  q.segregation_bins = n;
  const pb::LayerStats s = pb::layer_stats(bed, q);
  // Per unit cell 2r x 2r: one sphere, h = r + sqrt(r^2 - rho^2) over its disk, 0 outside.
  const double cell = 4 * r * r;
  const double density = (4.0 / 3.0 * pi * r * r * r) / (cell * 2 * r);  // pi / 6
  const double coverage = pi * r * r / cell;                              // pi / 4
  const double mean = (pi * r * r * r + 2.0 / 3.0 * pi * r * r * r) / cell;  // 5 pi r / 12
  // With u = h - r and c = mean - r over the disk (dA = 2 pi u du):
  //   integral |u - c| dA = 2 pi (c^3 / 3 + r^3 / 3 - c r^2 / 2);  integral h^2 dA = 17 pi r^4 / 6.
  const double c = mean - r;
  const double sa =
      ((cell - pi * r * r) * mean + 2 * pi * (c * c * c / 3 + r * r * r / 3 - c * r * r / 2)) / cell;
  const double sq = std::sqrt(17 * pi * r * r * r * r / 6 / cell - mean * mean);
  // The density is exact (spherical caps, no raster): rounding only.
  EXPECT_NEAR(s.density, density, 1e-12);
  EXPECT_NEAR(s.coverage, coverage, 5e-3 * coverage);
  EXPECT_NEAR(s.mean_height, mean, 5e-3 * mean);
  EXPECT_NEAR(s.sa, sa, 5e-3 * sa);
  EXPECT_NEAR(s.sq, sq, 5e-3 * sq);
  EXPECT_EQ(s.particles, static_cast<std::size_t>(n * n));
  // Equal spheres: no slope, and every bin holds its column of n spheres (6 bins, 6 columns).
  EXPECT_NEAR(s.segregation.slope, 0.0, 1e-12);
  for (std::size_t count : s.segregation.count) EXPECT_EQ(count, static_cast<std::size_t>(n));
}

TEST(SpreadLayer, HeightMapIsTheTopOfTheHighestSphere) {
  // One sphere on top of another: over their common centre line the height is the upper one's top.
  const double r = 10e-6;
  pb::Bed bed = square_monolayer(2, r);
  bed.add(2 * r, 2 * r, r + std::sqrt(2.0) * r, r);  // in the hollow of the four
  pb::LayerRequest q = request(bed, 3 * r, r / 10);
  const pb::LayerHeightMap m = pb::height_map(bed, q);
  // The cell centres nearest (2r, 2r) are (r/20, r/20) off it: h = zc + sqrt(r^2 - r^2/200).
  const std::size_t k = 19 * m.nx + 19;
  EXPECT_NEAR(m.height[k], r + std::sqrt(2.0) * r + std::sqrt(r * r - r * r / 200), 1e-12 * r);
  // The raster fits the window exactly: 40 x 40 cells of r/10.
  EXPECT_EQ(m.nx, 40u);
  EXPECT_EQ(m.ny, 40u);
  EXPECT_NEAR(m.dx, r / 10, 1e-15);
}

// ----------------------------------------------------------------------------- plane cuts

TEST(SpreadLayer, PlaneCutOfASphereIsASphericalCap) {
  // A sphere resting on the plate, a layer top at a fraction f of its diameter: the layer holds
  // the cap of height f 2r.
  const double r = 20e-6;
  pb::Bed bed;
  bed.domain.upper = {1e-3, 0.5e-3, 0.2e-3};
  bed.domain.periodic = {false, true, false};
  bed.add(0.5e-3, 0.25e-3, r, r);
  for (const double f : {0.1, 0.35, 0.5, 0.8}) {
    const double gap = 2 * r * f;
    const pb::LayerStats s = pb::layer_stats(bed, request(bed, gap, 5e-6));
    const double area = 1e-3 * 0.5e-3;
    // Exact caps: rounding only (relative 1e-12).
    EXPECT_NEAR(s.density * area * gap, cap_volume(r, gap), 1e-12 * cap_volume(r, gap)) << f;
  }
  // Cut by both planes (plate above the sphere's bottom): a slab = difference of two caps.
  pb::LayerStats s = pb::layer_stats(bed, [&] {
    pb::LayerRequest q = request(bed, 0.5 * r, 5e-6);
    q.plate = 0.5 * r;
    return q;
  }());
  const double slab = cap_volume(r, r) - cap_volume(r, 0.5 * r);
  EXPECT_NEAR(s.density * 1e-3 * 0.5e-3 * 0.5 * r, slab, 1e-12 * slab);
}

TEST(SpreadLayer, WindowCutsSpheresAndPeriodicImagesCountOnce) {
  const double r = 20e-6;
  pb::Bed bed;
  bed.domain.upper = {1e-3, 0.5e-3, 0.2e-3};
  bed.domain.periodic = {false, true, false};
  bed.add(0.4e-3, 0.25e-3, r, r);  // halved by the window's x0 = 0.4 mm
  bed.add(0.6e-3, 0.2 * r, r, r);  // wraps across y = 0: whole once (its image is the rest)
  pb::LayerRequest q = request(bed, 2 * r, r / 20);
  q.x0 = 0.4e-3;
  q.x1 = 0.8e-3;
  const pb::LayerStats s = pb::layer_stats(bed, q);
  const double v = 4.0 / 3.0 * pi * r * r * r;
  const double expected = 1.5 * v / (0.4e-3 * 0.5e-3 * 2 * r);
  EXPECT_NEAR(s.density, expected, 1e-12 * expected);
  // Coverage sees the wrapped sphere on both sides of y = 0: two full disks minus half of one.
  const double covered = 1.5 * pi * r * r / (0.4e-3 * 0.5e-3);
  // Raster r/20: a disk centred on a cell corner (the first) is sampled 0.6 % high, the second
  // (offset) 0.1 % (the lattice-point count in a circle, computed once with numpy); 2 %.
  EXPECT_NEAR(s.coverage, covered, 0.02 * covered);
}

// ----------------------------------------------------------------------------- segregation

TEST(SpreadLayer, SegregationSlopeHasTheSignAndSizeOfTheTrend) {
  // Diameters growing linearly with x, d = d0 + b x: the least-squares slope is b exactly; the
  // mirrored bed gives -b.
  const double d0 = 20e-6, b = 0.02;  // 20 um over 1 mm
  for (const double sign : {1.0, -1.0}) {
    pb::Bed bed;
    bed.domain.upper = {1e-3, 0.2e-3, 0.2e-3};
    bed.domain.periodic = {false, true, false};
    for (int i = 0; i < 20; ++i) {
      const double x = 0.05e-3 + i * 0.045e-3;
      const double d = sign > 0 ? d0 + b * x : d0 + b * (1e-3 - x);
      bed.add(x, 0.1e-3, 0.5 * d, 0.5 * d);
    }
    pb::LayerRequest q = request(bed, 60e-6, 5e-6);
    q.segregation_bins = 4;
    const pb::LayerStats s = pb::layer_stats(bed, q);
    // Least squares on an exact line: rounding only.
    EXPECT_NEAR(s.segregation.slope, sign * b, 1e-9 * b);
    EXPECT_EQ(s.segregation.count.size(), 4u);
    if (sign > 0) {
      EXPECT_LT(s.segregation.mean_diameter.front(), s.segregation.mean_diameter.back());
    } else {
      EXPECT_GT(s.segregation.mean_diameter.front(), s.segregation.mean_diameter.back());
    }
  }
}

// ----------------------------------------------------------------------------- KS

TEST(SpreadLayer, KsOfIdenticalSamplesIsZero) {
  pb::Rng rng(7);
  const pb::Psd psd = pb::Psd::parse("lognormal:d10=15e-6,d50=25e-6,d90=45e-6");
  std::vector<double> a;
  for (int i = 0; i < 500; ++i) a.push_back(2 * psd.sample_radius(rng));
  const pb::KsTest t = pb::ks_two_sample(a, a);
  EXPECT_EQ(t.d, 0.0);
  EXPECT_EQ(t.p, 1.0);
  EXPECT_EQ(t.n1, 500u);
  // Disjoint samples: D = 1, and p is tiny (lambda = (sqrt(250) + 0.12 + ...) ~ 15.9).
  std::vector<double> b = a;
  for (double& d : b) d += 1e-3;
  const pb::KsTest u = pb::ks_two_sample(a, b);
  EXPECT_EQ(u.d, 1.0);
  EXPECT_LT(u.p, 1e-100);
}

TEST(SpreadLayer, KsAgainstItsOwnPsdIsNotRejected) {
  // 2000 draws of a PSD against that PSD: D ~ 0.87 / sqrt(2000) = 0.02 on average; seed fixed,
  // the one-sample p must not reject at 1 % (a 1 % chance for an arbitrary seed, none here).
  pb::Rng rng(11);
  const pb::Psd psd = pb::Psd::parse("lognormal:d10=15e-6,d50=25e-6,d90=45e-6");
  std::vector<double> d;
  for (int i = 0; i < 2000; ++i) d.push_back(2 * psd.sample_radius(rng));
  const pb::KsTest t = pb::ks_against_psd(d, psd);
  EXPECT_LT(t.d, 1.63 / std::sqrt(2000.0));  // the 1 % critical value
  EXPECT_GT(t.p, 0.01);
}

TEST(SpreadLayer, KolmogorovTailMatchesTables) {
  // Q_KS(1) = 1 - 0.7300003283 (Kolmogorov's distribution, e.g. Marsaglia, Tsang & Wang 2003,
  // J. Stat. Softw. 8(18)); Q_KS(1.3581) = 0.05 to the 4 digits of the classical 5 % point.
  EXPECT_NEAR(pb::kolmogorov_tail(1.0), 0.2699996717, 1e-9);
  EXPECT_NEAR(pb::kolmogorov_tail(1.3581), 0.05, 1e-4);
  // The two series meet at lambda = 1.18 to double precision (both have converged there).
  EXPECT_NEAR(pb::kolmogorov_tail(1.18 - 1e-12), pb::kolmogorov_tail(1.18), 1e-10);
  EXPECT_EQ(pb::kolmogorov_tail(0.0), 1.0);
}

// ----------------------------------------------------------------------------- bad input

TEST(SpreadLayer, RefusesBadRequests) {
  const pb::Bed bed = square_monolayer(2, 10e-6);
  auto refused = [&](auto edit) {
    pb::LayerRequest q = request(bed, 20e-6, 1e-6);
    edit(q);
    EXPECT_THROW(pb::layer_stats(bed, q), powderbed::InputError);
  };
  refused([](pb::LayerRequest& q) { q.gap = 0; });
  refused([](pb::LayerRequest& q) { q.gap = -1e-6; });
  refused([](pb::LayerRequest& q) { q.raster = 0; });
  refused([](pb::LayerRequest& q) { q.raster = 1e-12; });  // 1.6e9 cells
  refused([](pb::LayerRequest& q) { q.x1 = q.x0; });
  refused([](pb::LayerRequest& q) { q.x1 = 1.0; });        // beyond the domain
  refused([](pb::LayerRequest& q) { q.plate = -1e-3; });
  refused([](pb::LayerRequest& q) { q.segregation_bins = 0; });
  pb::Bed flat = bed;
  flat.domain.dimension = 2;
  flat.domain.upper[2] = 0;
  EXPECT_THROW(pb::layer_stats(flat, request(bed, 20e-6, 1e-6)), powderbed::InputError);
}
