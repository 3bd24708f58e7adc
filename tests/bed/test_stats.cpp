// Bed statistics of docs/physics.md §2 against closed forms: caps, lattices, crafted contacts, g(r) of
// an uncorrelated bed, and Laguerre cells of lattices.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/lattice.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/bed/stats.hpp"

namespace pb = powderbed::bed;
using std::numbers::pi;

namespace {

double sphere_volume(double r) { return 4.0 / 3.0 * pi * r * r * r; }

// Composite Simpson rule with `panels` (even) panels.
template <class F>
double simpson(F f, double a, double b, int panels) {
  const double h = (b - a) / panels;
  double sum = f(a) + f(b);
  for (int k = 1; k < panels; ++k) sum += f(a + k * h) * (k % 2 ? 4 : 2);
  return sum * h / 3;
}

// Appends a particle without Bed::add's search for the next id (ids are 0..n-1 here).
void append(pb::Bed& bed, double x, double y, double z, double r) {
  bed.id.push_back(bed.n());
  bed.x.push_back(x);
  bed.y.push_back(y);
  bed.z.push_back(z);
  bed.radius.push_back(r);
}

pb::Bed single(int dimension, double x, double y, double z, double r) {
  pb::Bed bed;
  bed.domain.dimension = dimension;
  if (dimension == 2) bed.domain.upper[2] = 0;
  bed.add(x, y, z, r);
  return bed;
}

// ----------------------------------------------------------------------------- caps

TEST(Caps, SphereSlabMatchesQuadrature) {
  const double r = 2.0, zc = 0.3;
  const double slabs[][2] = {{-5, 5}, {0.3, 5}, {-1, 0.5}, {1.9, 2.2}, {-1.7, -1.6}, {2.4, 3}};
  for (const auto& s : slabs) {
    const double a = std::max(s[0], zc - r), b = std::min(s[1], zc + r);
    const double expected =
        b > a ? simpson([&](double z) { return pi * (r * r - (z - zc) * (z - zc)); }, a, b, 100)
              : 0.0;
    // Simpson's rule is exact for the quadratic integrand: only rounding (~1e-15) remains.
    EXPECT_NEAR(pb::sphere_slab_volume(r, zc, s[0], s[1]), expected, 1e-13 * sphere_volume(r))
        << "slab [" << s[0] << ", " << s[1] << "]";
  }
  // Full sphere and hemisphere: closed forms, rounding only.
  EXPECT_NEAR(pb::sphere_slab_volume(r, zc, -10, 10), sphere_volume(r), 1e-14 * sphere_volume(r));
  EXPECT_NEAR(pb::sphere_slab_volume(r, zc, zc, 10), 0.5 * sphere_volume(r),
              1e-14 * sphere_volume(r));
  EXPECT_THROW(pb::sphere_slab_volume(-1, 0, 0, 1), powderbed::InputError);
  EXPECT_THROW(pb::sphere_slab_volume(1, 0, 1, 0), powderbed::InputError);
}

TEST(Caps, DiskStripMatchesQuadrature) {
  const double r = 1.5, yc = -0.2;
  const double strips[][2] = {{-5, 5}, {-0.2, 5}, {-1, 0.5}, {1.1, 1.2}, {-1.69, -1.6}};
  for (const auto& s : strips) {
    // y = yc + r sin(t): integrand 2 r^2 cos^2 t is smooth, Simpson error ~ h^4 < 1e-13 here.
    const double t0 = std::asin(std::clamp((s[0] - yc) / r, -1.0, 1.0));
    const double t1 = std::asin(std::clamp((s[1] - yc) / r, -1.0, 1.0));
    const double expected =
        simpson([&](double t) { return 2 * r * r * std::cos(t) * std::cos(t); }, t0, t1, 2000);
    EXPECT_NEAR(pb::disk_strip_area(r, yc, s[0], s[1]), expected, 1e-12 * pi * r * r)
        << "strip [" << s[0] << ", " << s[1] << "]";
  }
  EXPECT_NEAR(pb::disk_strip_area(r, yc, -9, 9), pi * r * r, 1e-14 * pi * r * r);
  EXPECT_NEAR(pb::disk_strip_area(r, yc, yc, 9), 0.5 * pi * r * r, 1e-14 * pi * r * r);
}

// ----------------------------------------------------------------------------- sphere ∩ box

// Sphere volume inside the unit box, as packing_density of a one-particle bed.
double inside_unit_box(double x, double y, double z, double r) {
  return pb::packing_density(single(3, x, y, z, r));
}

TEST(PackingDensity, SpheresCutByBoxFacesEdgesAndCorners) {
  // Quadrature tolerance 1e-12 (tanh-sinh between the breakpoints): compare at 1e-11 relative.
  const double tol = 1e-11;
  const double r = 0.3;
  EXPECT_NEAR(inside_unit_box(0, 0, 0, r), sphere_volume(r) / 8, tol * sphere_volume(r));
  EXPECT_NEAR(inside_unit_box(0, 1, 0.5, r), sphere_volume(r) / 4, tol * sphere_volume(r));
  EXPECT_NEAR(inside_unit_box(0.5, 0.5, 1, r), sphere_volume(r) / 2, tol * sphere_volume(r));
  // Cut through the centre by x = 0 (halves it) and off-centre by y = 0.
  EXPECT_NEAR(inside_unit_box(0, 0.2, 0.5, 0.5), 0.5 * pb::sphere_slab_volume(0.5, 0.2, 0, 1),
              tol * sphere_volume(0.5));
  // Same with the corner z = 0 through the centre too: a quarter of the slab.
  EXPECT_NEAR(inside_unit_box(0, 0.1, 0, 0.3), 0.25 * pb::sphere_slab_volume(0.3, 0.1, 0, 1),
              tol * sphere_volume(0.3));
}

TEST(PackingDensity, GenericCornerAgainstIndependentQuadrature) {
  // Centre (0.1, 0.15, 0.2), r = 0.3: cut off-centre by x = 0, y = 0 and z = 0 at once.
  const double xc = 0.1, yc = 0.15, zc = 0.2, r = 0.3;
  // Reference: midpoint rule over (x, y) of the z-chord clipped to z >= 0. The chord length has
  // a square-root edge at the sphere's outline, so the error is ~h^1.5 ~ 1e-6 relative for
  // 3000 x 3000 points; the tolerance is 1e-5 relative.
  const int n = 3000;
  const double x0 = 0, x1 = xc + r, y0 = 0, y1 = yc + r;
  const double hx = (x1 - x0) / n, hy = (y1 - y0) / n;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double x = x0 + (i + 0.5) * hx;
    for (int j = 0; j < n; ++j) {
      const double y = y0 + (j + 0.5) * hy;
      const double rho2 = (x - xc) * (x - xc) + (y - yc) * (y - yc);
      if (rho2 >= r * r) continue;
      const double h = std::sqrt(r * r - rho2);
      sum += std::max(0.0, zc + h - std::max(0.0, zc - h));
    }
  }
  const double expected = sum * hx * hy;
  EXPECT_NEAR(inside_unit_box(xc, yc, zc, r), expected, 1e-5 * expected);
}

TEST(PackingDensity, DisksCutByRectangle) {
  const double r = 0.3;
  // Quarter and half disks: closed forms (the disk ∩ rectangle area is exact), rounding only.
  EXPECT_NEAR(pb::packing_density(single(2, 0, 0, 0, r)), pi * r * r / 4, 1e-14);
  EXPECT_NEAR(pb::packing_density(single(2, 0.5, 1, 0, r)), pi * r * r / 2, 1e-14);
  // Generic corner (0.1, 0.2): x = xc + r sin t, the clipped y-chord has kinks, so Simpson
  // converges as h^2: 2e5 panels give ~1e-11; tolerance 1e-9.
  const double xc = 0.1, yc = 0.2;
  const double t0 = std::asin(-xc / r);
  const double expected = simpson(
      [&](double t) {
        const double half = r * std::cos(t);
        return std::max(0.0, yc + half - std::max(0.0, yc - half)) * r * std::cos(t);
      },
      t0, pi / 2, 200000);
  EXPECT_NEAR(pb::packing_density(single(2, xc, yc, 0, r)), expected, 1e-9);
}

// ----------------------------------------------------------------------------- lattices

TEST(Lattice, SimpleCubicDensityAndContacts) {
  const pb::Bed bed = pb::simple_cubic_lattice(10, 0.5);
  // Every sphere lies inside the box (touching the faces): the density is the exact sum of
  // whole-sphere volumes, 1000 (4/3 pi r^3) / (20 r)^3 = pi/6, up to rounding (~1e-15).
  EXPECT_NEAR(pb::packing_density(bed), pi / 6, 1e-12);
  const pb::ContactStats s = pb::contact_stats(bed, 1e-6);
  // Touching pairs along each axis: 3 axes x 10 x 10 rows x 9 links = 2700; Z = 5400/1000.
  EXPECT_EQ(s.contacts, 2700u);
  EXPECT_DOUBLE_EQ(s.coordination, 5.4);
  EXPECT_EQ(s.wall_contacts, 600u);  // 6 faces x 100 spheres
  EXPECT_EQ(s.rattlers, 0u);
  // Contacts per particle: 8 corners (3), 12 x 8 edge (4), 6 x 64 face (5), 512 inside (6).
  ASSERT_EQ(s.histogram.size(), 7u);
  EXPECT_EQ(s.histogram[3], 8u);
  EXPECT_EQ(s.histogram[4], 96u);
  EXPECT_EQ(s.histogram[5], 384u);
  EXPECT_EQ(s.histogram[6], 512u);
  EXPECT_DOUBLE_EQ(pb::max_relative_overlap(bed), 0.0);
}

TEST(Lattice, FccPeriodic) {
  const pb::Bed bed = pb::fcc_lattice(3, 1.0);
  // Periodic on every axis: no sphere is cut, density = 4 spheres / a^3 exactly (rounding only).
  EXPECT_NEAR(pb::packing_density(bed), pi / (3 * std::sqrt(2.0)), 1e-12);
  const pb::ContactStats s = pb::contact_stats(bed, 1e-6);
  EXPECT_EQ(s.contacts, 6 * bed.n());
  EXPECT_DOUBLE_EQ(s.coordination, 12.0);
  EXPECT_EQ(s.wall_contacts, 0u);
  ASSERT_EQ(s.histogram.size(), 13u);
  EXPECT_EQ(s.histogram[12], bed.n());
}

TEST(Lattice, HexagonalPeriodic2d) {
  const pb::Bed bed = pb::hexagonal_lattice_2d(10, 10, 1.0);
  EXPECT_NEAR(pb::packing_density(bed), pi / (2 * std::sqrt(3.0)), 1e-12);  // rounding only
  const pb::ContactStats s = pb::contact_stats(bed, 1e-6);
  EXPECT_DOUBLE_EQ(s.coordination, 6.0);
  EXPECT_EQ(s.wall_contacts, 0u);
}

TEST(Lattice, SimpleCubicLayerDensityAndProfile) {
  const double r = 0.5;
  const pb::Bed bed = pb::simple_cubic_lattice(10, r);
  // Layer z in [r/2, 3r/2] through the bottom row's centres: each sphere contributes
  // pi (2 r^2 h - 2 h^3 / 3) with h = r/2, over (20 r)^2 x r: phi = 11 pi / 48. Closed form.
  EXPECT_NEAR(pb::layer_density(bed, r / 2, 3 * r / 2), 11 * pi / 48, 1e-12);
  // Bottom half-layer [0, r]: hemispheres, phi = pi / 6.
  EXPECT_NEAR(pb::layer_density(bed, 0, r), pi / 6, 1e-12);
  EXPECT_THROW(pb::layer_density(bed, 1, 1), powderbed::InputError);
  // The profile's mean over equal bins is the box density (exact caps: rounding only).
  const pb::Series profile = pb::density_profile(bed, 37);
  ASSERT_EQ(profile.y.size(), 37u);
  double mean = 0;
  for (const double y : profile.y) mean += y / 37;
  EXPECT_NEAR(mean, pb::packing_density(bed), 1e-12);
  EXPECT_NEAR(profile.x.front(), 10 * r / 37, 1e-12);
}

TEST(Lattice, HexagonalLayersAcrossThePeriodicFace) {
  // 2D layers run along y, which is periodic here: the bottom row of disks (centres at
  // 0.866 r) crosses y = 0 and its images must fill the top layer. Disk areas are closed
  // forms, so only rounding remains.
  const pb::Bed bed = pb::hexagonal_lattice_2d(10, 10, 1.0);
  const double phi = pi / (2 * std::sqrt(3.0));
  const double row = std::sqrt(3.0);  // one period of the lattice in y
  EXPECT_NEAR(pb::layer_density(bed, 0, row), phi, 1e-12);
  EXPECT_NEAR(pb::layer_density(bed, 3.3 * row, 4.3 * row), phi, 1e-12);
  const pb::Series profile = pb::density_profile(bed, 20);  // two bins per row
  double mean = 0;
  for (const double y : profile.y) mean += y / 20;
  EXPECT_NEAR(mean, phi, 1e-12);
  EXPECT_NEAR(profile.y.front(), profile.y.back(), 1e-12);  // symmetric about a row's middle
}

TEST(Lattice, DensityProfileOfCutSpheresIntegratesToBoxDensity) {
  // Spheres sticking out of every face (edges and corners cut: the quadrature path).
  pb::Bed bed = pb::fcc_lattice(2, 1.0);
  bed.domain.periodic = {false, false, false};
  const pb::Series profile = pb::density_profile(bed, 16);
  double mean = 0;
  for (const double y : profile.y) mean += y / 16;
  // Quadrature tolerance 1e-12 per cut sphere; 1e-10 absolute on phi is ample.
  EXPECT_NEAR(mean, pb::packing_density(bed), 1e-10);
}

// ----------------------------------------------------------------------------- contacts

TEST(Contacts, RattlerAndTolerance) {
  pb::Bed bed = pb::simple_cubic_lattice(3, 1.0);
  // A small sphere at the centre of the first cube of 8: sqrt(3) > 1 + 0.5, no contact.
  bed.add(2, 2, 2, 0.5);
  pb::ContactStats s = pb::contact_stats(bed, 1e-6);
  EXPECT_EQ(s.rattlers, 1u);
  ASSERT_EQ(s.histogram.size(), 7u);
  EXPECT_EQ(s.histogram[0], 1u);
  EXPECT_EQ(s.histogram[3], 8u);
  EXPECT_EQ(s.histogram[4], 12u);
  EXPECT_EQ(s.histogram[5], 6u);
  EXPECT_EQ(s.histogram[6], 1u);

  // Two spheres with a relative gap of 1e-4: in contact at tol 1e-3, not at 1e-6.
  pb::Bed pair;
  pair.domain.upper = {10, 10, 10};
  pair.add(5, 5, 5, 1);
  pair.add(5, 5, 7.0002, 1);
  EXPECT_EQ(pb::contact_stats(pair, 1e-6).contacts, 0u);
  EXPECT_EQ(pb::contact_stats(pair, 1e-3).contacts, 1u);
  EXPECT_DOUBLE_EQ(pb::contact_stats(pair, 1e-3).coordination, 1.0);
  EXPECT_THROW(pb::contact_stats(pair, -1), powderbed::InputError);
  EXPECT_EQ(pb::contact_stats(pb::Bed{}, 1e-6).coordination, 0.0);
}

// A particle resting on the floor (or leaning on a wall) with no particle contact is held, not a
// rattler; one floating free is; the contacts histogram still counts particle contacts only.
TEST(Contacts, ParticlesOnTheFloorOrAWallAreNotRattlers) {
  pb::Bed bed;
  bed.domain.upper = {10, 10, 10};
  bed.add(5, 5, 1, 1);  // on the floor z = 0
  bed.add(1, 8, 5, 1);  // against the wall x = 0
  bed.add(5, 5, 5, 1);  // touching nothing
  const pb::ContactStats s = pb::contact_stats(bed, 1e-6);
  EXPECT_EQ(s.histogram[0], 3u);
  EXPECT_EQ(s.wall_contacts, 2u);
  EXPECT_EQ(s.rattlers, 1u);
  // Periodic in z, the floor holds nothing: the first becomes a rattler too.
  bed.domain.periodic = {false, false, true};
  EXPECT_EQ(pb::contact_stats(bed, 1e-6).rattlers, 2u);
}

TEST(Contacts, WallContacts2dUseOnlyXAndYFaces) {
  pb::Bed bed;
  bed.domain.dimension = 2;
  bed.domain.upper = {10, 10, 0};
  bed.add(1, 5, 0, 1);        // touches x = 0
  bed.add(9, 9, 0, 1);        // touches x = 10 and y = 10
  bed.add(5, 5, 0, 1);        // free
  EXPECT_EQ(pb::contact_stats(bed, 1e-6).wall_contacts, 3u);
  bed.domain.periodic = {true, false, false};
  EXPECT_EQ(pb::contact_stats(bed, 1e-6).wall_contacts, 1u);
}

TEST(Contacts, MaxRelativeOverlap) {
  pb::Bed bed;
  bed.domain.upper = {10, 10, 10};
  bed.add(2, 2, 2, 1);
  bed.add(4.7, 2, 2, 2);  // overlap 0.3 of 3
  bed.add(8, 8, 8, 1);
  // (3 - 2.7)/3 with the rounding of 4.7 - 2: ~1e-16.
  EXPECT_NEAR(pb::max_relative_overlap(bed), 0.1, 1e-14);
}

// ----------------------------------------------------------------------------- distributions

TEST(Distribution, RadiusHistogram) {
  pb::Bed bed;
  for (const double r : {1.0, 2.0, 3.0, 4.0}) bed.add(10 * r, 0, 0, r);
  const pb::Histogram h = pb::radius_histogram(bed, 3);
  ASSERT_EQ(h.edges.size(), 4u);
  EXPECT_EQ(h.edges.front(), 1.0);
  EXPECT_EQ(h.edges.back(), 4.0);
  EXPECT_EQ(h.counts, (std::vector<double>{1, 1, 2}));  // r = 2 opens bin 1; r = 4 closes bin 2
  EXPECT_TRUE(h.target.empty());
  EXPECT_THROW(pb::radius_histogram(bed, 0), powderbed::InputError);
}

TEST(Distribution, RadiusHistogramAgainstTargetPsd) {
  const pb::Psd psd = pb::Psd::parse("gauss:mean=2,sd=0.5,min=1,max=3,on=radius");
  pb::Rng rng(7);
  pb::Bed bed;
  const std::size_t n = 20000;
  for (std::size_t i = 0; i < n; ++i) append(bed, 0, 0, 0, psd.sample_radius(rng));
  const pb::Histogram h = pb::radius_histogram(bed, 10, &psd);
  EXPECT_EQ(h.edges.front(), 1.0);
  EXPECT_EQ(h.edges.back(), 3.0);
  double total = 0, counted = 0;
  for (std::size_t k = 0; k < 10; ++k) {
    total += h.target[k];
    counted += h.counts[k];
    // Binomial counts: 5 standard deviations (sqrt of the expected count) per bin.
    EXPECT_NEAR(h.counts[k], h.target[k], 5 * std::sqrt(h.target[k]) + 1) << "bin " << k;
  }
  EXPECT_NEAR(total, static_cast<double>(n), 1e-9 * static_cast<double>(n));  // the window holds all the mass
  EXPECT_EQ(counted, static_cast<double>(n));
}

TEST(Distribution, RadialDistributionOfPoissonBedIsOne) {
  // 20000 uncorrelated centres in the unit box (seed 3); r_max = 0.1, 20 bins of 0.005.
  pb::Bed bed;
  bed.domain.upper = {1, 1, 1};
  pb::Rng rng(3);
  const std::size_t n = 20000;
  bed.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = pb::uniform01(rng), y = pb::uniform01(rng), z = pb::uniform01(rng);
    append(bed, x, y, z, 1e-4);
  }
  const double r_max = 0.1;
  const pb::Series g = pb::radial_distribution(bed, r_max, 20);
  ASSERT_EQ(g.y.size(), 20u);
  const auto count = static_cast<double>(n);
  const double centres = count * std::pow(1 - 2 * r_max, 3);  // expected centre count
  for (std::size_t k = 10; k < 20; ++k) {
    const double r0 = 0.005 * static_cast<double>(k), r1 = r0 + 0.005;
    const double expected = centres * (count - 1) * 4.0 / 3.0 * pi * (r1 * r1 * r1 - r0 * r0 * r0);
    // Poisson counts, each pair of two centres counted twice: sd = sqrt(2 / expected count);
    // 5 sd (expected counts 3e4-1.2e5: 5 sd = 2-4 %).
    EXPECT_NEAR(g.y[k], 1.0, 5 * std::sqrt(2 / expected)) << "r = " << g.x[k];
  }
  EXPECT_THROW(pb::radial_distribution(bed, 0.6, 10), powderbed::InputError);  // no centres
}

TEST(Distribution, RadialDistributionOfFccPeaksAtContact) {
  const pb::Bed bed = pb::fcc_lattice(4, 1.0);  // periodic, L = 4 a = 11.3
  // 64 bins of 3/64: the contact distance 2 falls inside bin 42, not on an edge.
  const pb::Series g = pb::radial_distribution(bed, 3.0, 64);
  std::size_t peak = 0;
  for (std::size_t k = 0; k < g.y.size(); ++k) {
    if (g.y[k] > g.y[peak]) peak = k;
  }
  EXPECT_EQ(peak, 42u);
  for (std::size_t k = 0; k < 42; ++k) EXPECT_EQ(g.y[k], 0.0);
  // 12 neighbours per particle in that shell, exactly (integer counts; rounding only).
  const double r0 = 42 * 3.0 / 64, r1 = 43 * 3.0 / 64;
  const double density = static_cast<double>(bed.n() - 1) / std::pow(4 * 2 * std::sqrt(2.0), 3);
  EXPECT_NEAR(g.y[42] * density * 4.0 / 3.0 * pi * (r1 * r1 * r1 - r0 * r0 * r0), 12.0, 1e-10);
  EXPECT_THROW(pb::radial_distribution(bed, 6.0, 10), powderbed::InputError);  // > L/2
}

// ----------------------------------------------------------------------------- Voronoi

TEST(Voronoi, FccInteriorCellsAreRhombicDodecahedra) {
  pb::Bed bed = pb::fcc_lattice(3, 1.0);
  bed.domain.periodic = {false, false, false};
  const pb::VoronoiStats v = pb::voronoi_stats(bed);
  ASSERT_GT(v.interior, 0u);
  const double phi = pi / (3 * std::sqrt(2.0));
  std::size_t interior = 0;
  for (const double f : v.local_fraction) {
    if (std::isnan(f)) continue;
    ++interior;
    // Circumcentres of the degenerate (cospherical) lattice are built in doubles: ~1e-15
    // relative each; 1e-9 relative is a wide margin.
    EXPECT_NEAR(f, phi, 1e-9 * phi);
  }
  EXPECT_EQ(interior, v.interior);
  EXPECT_NEAR(v.mean, phi, 1e-9 * phi);
  EXPECT_LT(v.sd, 1e-9);
}

TEST(Voronoi, SimpleCubicInteriorCellsAreCubes) {
  const pb::Bed bed = pb::simple_cubic_lattice(5, 1.0);
  const pb::VoronoiStats v = pb::voronoi_stats(bed);
  EXPECT_EQ(v.interior, 27u);  // the 3 x 3 x 3 core; the outer shell is on the hull
  EXPECT_NEAR(v.mean, pi / 6, 1e-9 * pi / 6);  // cube (2 r)^3 per sphere; rounding only
  EXPECT_TRUE(std::isnan(v.local_fraction[0]));
}

// Layers of two sizes: the simple cubic lattice (spacing a = 2) with radius 1 in the even z
// layers and 0.7 in the odd ones. Across x and y the neighbours are alike (radical planes
// halfway, at +-1); along z the plane lies t = (a^2 + r^2 - r'^2) / (2a) from the centre of
// radius r. The diagonal neighbours' planes only touch the box's edges and corners (e.g.
// x + z = 1 + t for the one at (2, 0, 2)), so every interior cell is the box 2 x 2 x 2t: the
// weighted case in closed form, where the cell is not centred on its sphere.
TEST(Voronoi, LayersOfTwoSizesHaveBoxCellsShiftedByTheWeights) {
  pb::Bed bed = pb::simple_cubic_lattice(5, 1.0);
  const double a = 2.0, big = 1.0, small = 0.7;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const long layer = std::lround((bed.z[i] - 1) / a);  // centres at 1, 3, 5, ...
    bed.radius[i] = layer % 2 == 0 ? big : small;
  }
  const pb::VoronoiStats v = pb::voronoi_stats(bed);
  EXPECT_EQ(v.interior, 27u);
  const auto expected = [&](double r, double other) {
    const double t = (a * a + r * r - other * other) / (2 * a);
    return 4.0 / 3.0 * pi * r * r * r / (2.0 * 2.0 * 2.0 * t);
  };
  for (std::size_t i = 0; i < bed.n(); ++i) {
    if (std::isnan(v.local_fraction[i])) continue;
    const double want = bed.radius[i] == big ? expected(big, small) : expected(small, big);
    // Circumcentres of the cospherical lattice in doubles, as in the FCC case.
    EXPECT_NEAR(v.local_fraction[i], want, 1e-9 * want) << "particle " << i;
  }
}

TEST(Voronoi, RandomNonOverlappingBedHasFractionsBelowOne) {
  // 500 spheres of radius 0.4-0.6 by random sequential addition in a 10^3 box (seed 5).
  // A non-overlapping sphere lies inside its own Laguerre cell, so 0 < phi_local < 1.
  pb::Bed bed;
  bed.domain.upper = {10, 10, 10};
  pb::Rng rng(5);
  while (bed.n() < 500) {
    const double r = pb::uniform(rng, 0.4, 0.6);
    const double x = pb::uniform(rng, r, 10 - r), y = pb::uniform(rng, r, 10 - r),
                 z = pb::uniform(rng, r, 10 - r);
    bool free = true;
    for (std::size_t j = 0; j < bed.n() && free; ++j) {
      const double dx = bed.x[j] - x, dy = bed.y[j] - y, dz = bed.z[j] - z;
      free = dx * dx + dy * dy + dz * dz > (r + bed.radius[j]) * (r + bed.radius[j]);
    }
    if (free) bed.add(x, y, z, r);
  }
  const pb::VoronoiStats v = pb::voronoi_stats(bed);
  EXPECT_GT(v.interior, 100u);
  for (const double f : v.local_fraction) {
    if (std::isnan(f)) continue;
    EXPECT_GT(f, 0.0);
    EXPECT_LT(f, 1.0);
  }
  EXPECT_GT(v.mean, 0.2);
  EXPECT_LT(v.mean, 0.6);
}

TEST(Voronoi, HiddenSphereIsNan) {
  pb::Bed bed = pb::simple_cubic_lattice(5, 1.0);
  const std::size_t centre = 62;  // the middle sphere, (5, 5, 5)
  bed.add(bed.x[centre] + 0.1, bed.y[centre], bed.z[centre], 0.2);  // inside it: hidden
  const pb::VoronoiStats v = pb::voronoi_stats(bed);
  EXPECT_TRUE(std::isnan(v.local_fraction.back()));
  EXPECT_EQ(v.interior, 27u);
}

TEST(Voronoi, RejectsTwoDimensionalBeds) {
  EXPECT_THROW(pb::voronoi_stats(pb::hexagonal_lattice_2d(4, 4, 1.0)), powderbed::InputError);
}

}  // namespace
