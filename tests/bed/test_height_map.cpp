// bed::HeightMap (the fused solid's top, spread on by dem and conducted through by thermal):
// bilinear between nodes and held beyond them, the nearest surface point of a sphere, and the
// seam of a periodic box.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numeric>

#include "powderbed/bed/height_map.hpp"
#include "powderbed/bed/surface_contacts.hpp"

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
  EXPECT_NEAR(bed::surface_overlap(flat, 10e-6, 10e-6, 4e-6, 5e-6), 1e-6, 1e-18);
  EXPECT_LE(bed::surface_overlap(flat, 10e-6, 10e-6, 6e-6, 5e-6), 0.0);
  // A centre below the surface reaches r plus its depth into it.
  EXPECT_NEAR(bed::surface_overlap(flat, 10e-6, 10e-6, -1e-6, 5e-6), 6e-6, 1e-18);
  // A step beside the foot is found: node (2, 1) raised 8 um, a sphere of 5 um at x = 15 um
  // resting 5.5 um above the floor touches the step's flank though the floor under it is clear.
  flat.z[2 + 3 * 1] = 8e-6;
  EXPECT_GT(bed::surface_overlap(flat, 13e-6, 10e-6, 5.5e-6, 5e-6), 0.0);
}

TEST(HeightMap, PeriodicSeamKeepsTheVolume) {
  bed::HeightMap m = plane();
  const double before = std::accumulate(m.z.begin(), m.z.end(), 0.0);
  m.periodic_y = true;
  m.join_periodic_edges();
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(m.node(i, 0), m.node(i, 2));
  EXPECT_NEAR(std::accumulate(m.z.begin(), m.z.end(), 0.0), before, 1e-20);
}

namespace {

// 5 x 5 nodes 10 um apart, periodic along y (period 40 um: node row 4 is row 0): a ridge 6 um
// high along x on row 3, 10 um across the seam from row 0; `periods` of them stacked along y on
// a bounded grid is the same surface written out.
bed::HeightMap ridge(std::size_t periods) {
  bed::HeightMap m;
  m.nx = 5;
  m.ny = 4 * periods + 1;
  m.dx = m.dy = 10e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.z.push_back(j % 4 == 3 ? 6e-6 : 0.0);
  m.periodic_y = periods == 1;
  return m;
}

}  // namespace

// A sphere near the seam of a periodic surface touches what lies across it: its contacts are
// those of the same sphere one period further on the surface written out over three periods,
// on both sides of the seam, and the same at y and at y + period. Held flat beyond the edge
// (bounded), the ridge across the seam went unseen until the sphere crossed, and the overlap
// jumped (docs/results/build-layers.md).
TEST(HeightMap, PeriodicSurfaceIsTheSurfaceWrittenOutAcrossTheSeam) {
  const bed::HeightMap seam = ridge(1), written = ridge(3);
  const double period = 40e-6, r = 8e-6;
  for (const double y : {1e-6, 3e-6, 39e-6, -2e-6}) {
    std::array<bed::SurfaceContact, bed::kMaxSurfaceContacts> a, b;
    const std::size_t na = bed::surface_contacts(seam, 20e-6, y, 7e-6, r, a);
    const std::size_t nb = bed::surface_contacts(written, 20e-6, y + period, 7e-6, r, b);
    ASSERT_EQ(na, nb) << "y " << y;
    ASSERT_GE(na, y == 1e-6 ? 2u : 1u) << "y " << y << ": at 1 um, the plane and the ridge's slope across the seam";
    for (std::size_t k = 0; k < na; ++k) {
      EXPECT_NEAR(a[k].distance, b[k].distance, 1e-18) << "y " << y << " contact " << k;
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(a[k].offset[d], b[k].offset[d], 1e-18);
    }
    EXPECT_NEAR(bed::surface_overlap(seam, 20e-6, y, 7e-6, r), bed::surface_overlap(seam, 20e-6, y + period, 7e-6, r), 1e-18);
  }
  // The bounded grid held flat beyond its edge sees the plane alone at y = 1 um.
  bed::HeightMap bounded = seam;
  bounded.periodic_y = false;
  EXPECT_NEAR(bed::surface_overlap(bounded, 20e-6, 1e-6, 7e-6, r), 1e-6, 1e-15);
  EXPECT_GT(bed::surface_overlap(seam, 20e-6, 1e-6, 7e-6, r), 1.4e-6);
}

// Ericson's regions: a point over the face projects onto it; beyond an edge it meets the edge at
// the foot of its perpendicular; beyond a corner, the corner.
TEST(ClosestPointOnTriangle, FaceEdgeAndCorner) {
  const bed::Point3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const auto face = bed::closest_point_on_triangle({0.25, 0.25, 2}, a, b, c);
  EXPECT_EQ(face.feature, bed::TriangleFeature::face);
  EXPECT_DOUBLE_EQ(face.point[0], 0.25);
  EXPECT_DOUBLE_EQ(face.point[2], 0.0);
  const auto edge = bed::closest_point_on_triangle({0.7, 0.7, 1}, a, b, c);  // beyond bc
  EXPECT_EQ(edge.feature, bed::TriangleFeature::edge_bc);
  EXPECT_DOUBLE_EQ(edge.point[0], 0.5);
  EXPECT_DOUBLE_EQ(edge.point[1], 0.5);
  const auto corner = bed::closest_point_on_triangle({-1, -2, 0.5}, a, b, c);
  EXPECT_EQ(corner.feature, bed::TriangleFeature::vertex_a);
}

// On a plane the triangles are the plane: the nearest point of a centre h above it lies
// h / sqrt(1 + |grad h|^2) away along its normal, wherever the centre is over the grid.
TEST(HeightMap, NearestPointOnAPlaneLiesAlongItsNormal) {
  const bed::HeightMap m = plane();  // grad h = (0.1, 0.2)
  const double norm = std::sqrt(1 + 0.01 + 0.04);
  for (const auto& [x, y] : {std::pair{5e-6, 15e-6}, std::pair{12.5e-6, 7.5e-6}, std::pair{10e-6, 10e-6}}) {
    EXPECT_NEAR(m.surface(x, y), m.at(x, y), 1e-18);
    std::array<bed::SurfaceContact, bed::kMaxSurfaceContacts> c;
    ASSERT_EQ(bed::surface_contacts(m, x, y, m.at(x, y) + 3e-6, 5e-6, c), 1u);
    const bed::SurfaceContact& p = c[0];
    EXPECT_NEAR(p.distance, 3e-6 / norm, 1e-15);
    EXPECT_NEAR(p.offset[0] / p.distance, 0.1 / norm, 1e-9);
    EXPECT_NEAR(p.offset[1] / p.distance, 0.2 / norm, 1e-9);
  }
}

// A sphere in a V-shaped valley touches both slopes at the same distance; one on the ridge of
// the inverted valley touches the ridge's edge once; one over a plane of many triangles touches
// it once (the edges it is near are not contacts of their own).
TEST(SurfaceContacts, ValleyTwiceRidgeOncePlaneOnce) {
  const auto groove = [](double sign) {
    bed::HeightMap m;
    m.nx = m.ny = 21;
    m.dx = m.dy = 10e-6;
    for (std::size_t j = 0; j < m.ny; ++j)
      for (std::size_t i = 0; i < m.nx; ++i) m.z.push_back(50e-6 + sign * 0.3 * std::abs(10e-6 * static_cast<double>(i) - 100e-6));
    return m;
  };
  std::array<bed::SurfaceContact, bed::kMaxSurfaceContacts> c;
  const double r = 15e-6, slope_distance = r - 0.1e-6;
  // Over the valley's floor line at the height where each slope lies r - 0.1 um away.
  const double z = 50e-6 + slope_distance * std::sqrt(1 + 0.09) / 1.0;
  ASSERT_EQ(bed::surface_contacts(groove(1), 100e-6, 97e-6, z, r, c), 2u);
  EXPECT_NEAR(c[0].distance, slope_distance, 1e-12);
  EXPECT_NEAR(c[1].distance, slope_distance, 1e-12);
  EXPECT_NEAR(c[0].offset[0], -c[1].offset[0], 1e-15);
  // Over the ridge: its edge, once, straight down.
  ASSERT_EQ(bed::surface_contacts(groove(-1), 100e-6, 97e-6, 50e-6 + slope_distance, r, c), 1u);
  EXPECT_NEAR(c[0].distance, slope_distance, 1e-15);
  EXPECT_NEAR(c[0].offset[0], 0.0, 1e-18);
  // Over a slope of the valley, away from its floor line and across the cells' edges and
  // diagonals: one contact.
  for (const double x : {130e-6, 135e-6, 140e-6})
    EXPECT_EQ(bed::surface_contacts(groove(1), x, 95e-6, groove(1).at(x, 95e-6) + 14e-6, r, c), 1u) << x;
}

// The triangles found once near a sphere (triangles_near, within r plus a margin) give the same
// contacts as the search of the whole surface wherever the sphere goes within that margin,
// including across a periodic seam it is wrapped over (the spread keeps such a list per
// particle between prunes of its neighbour list): on a rough periodic surface, 2000 spheres
// resting at random on it, each moved by up to the margin, bit for bit.
TEST(HeightMap, TrianglesFoundOnceGiveTheContactsOfTheWholeSurface) {
  bed::HeightMap m;
  m.nx = 13;
  m.ny = 9;
  m.dx = m.dy = 10e-6;
  m.periodic_x = m.periodic_y = true;
  std::uint64_t state = 12345;
  const auto uniform = [&state] {  // xorshift: no library stream needed for a rough surface
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  for (std::size_t k = 0; k < m.nx * m.ny; ++k) m.z.push_back(8e-6 * uniform());
  m.join_periodic_edges();
  const double lx = m.period_x(), ly = m.period_y(), margin = 1.5e-6;
  std::size_t touching = 0, several = 0;
  for (int n = 0; n < 2000; ++n) {
    const double r = 6e-6 + 8e-6 * uniform();
    const double x = lx * uniform(), y = ly * uniform();
    const double z = m.at(x, y) + r * (0.6 + 0.5 * uniform());
    std::vector<bed::TriangleImage> near;
    bed::triangles_near(m, x, y, z, r + margin, near);
    // Moved by up to the margin, then wrapped into the period as the spread wraps its particles.
    const double step = margin / std::sqrt(3.0);
    const double ux = x + step * (2 * uniform() - 1), uy = y + step * (2 * uniform() - 1);
    const double zc = z + step * (2 * uniform() - 1);
    const double wx = bed::wrap_into(ux, 0, lx), wy = bed::wrap_into(uy, 0, ly);
    const std::array<std::ptrdiff_t, 2> wrapped{std::lround((wx - x) / lx) * static_cast<std::ptrdiff_t>(m.nx - 1),
                                                std::lround((wy - y) / ly) * static_cast<std::ptrdiff_t>(m.ny - 1)};
    std::array<bed::SurfaceContact, bed::kMaxSurfaceContacts> all, listed;
    const std::size_t na = bed::surface_contacts(m, wx, wy, zc, r, all);
    const std::size_t nb = bed::surface_contacts(m, wx, wy, zc, r, near, wrapped, listed);
    ASSERT_EQ(na, nb) << "sphere " << n;
    for (std::size_t k = 0; k < na; ++k) {
      EXPECT_EQ(all[k].facet, listed[k].facet) << "sphere " << n;
      EXPECT_EQ(all[k].distance, listed[k].distance) << "sphere " << n;
      for (int d = 0; d < 3; ++d) EXPECT_EQ(all[k].offset[d], listed[k].offset[d]) << "sphere " << n;
    }
    touching += na > 0 ? 1 : 0;
    several += na > 1 ? 1 : 0;
  }
  // The draw must exercise the search: most spheres touch, and some touch several facets.
  EXPECT_GT(touching, 1000u);
  EXPECT_GT(several, 50u);
}
