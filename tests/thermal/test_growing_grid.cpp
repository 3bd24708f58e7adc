// The substrate grid grows with the part (substrate.hpp, docs/sinter.md "The solver on a raised
// top"): a raised column gets node planes of its own, its top node stays under 1.5 dz thick,
// and a part raised by whole planes conducts exactly as the deeper plate it then is.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "powderbed/thermal/solver.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;

namespace {

constexpr double kDz = 5e-6;  // grid spacing, m

std::size_t nodes(double length) { return static_cast<std::size_t>(std::llround(length / kDz)) + 1; }

// A bare plate lx × ly under one Beer–Lambert track along y = ly/2 (substrate heating only),
// `depth` deep on the grid kDz.
thermal::SinterScene plate_scene(double lx, double ly, double depth) {
  thermal::SinterScene scene =
      test::small_scene(thermal::kLaserSubstrate, {nodes(lx), nodes(ly), nodes(depth)}, depth);
  scene.power = 100;
  scene.speed = 1.0;
  scene.start_x = 20e-6;
  scene.end_x = lx - 20e-6;
  return scene;
}

// Every column's top node is its own plane's: the column's height lies less than one dz above
// that node (so the node owns dz/2 + δ < 1.5 dz), except where the grid's last plane lumps more.
void expect_thin_top_nodes(const thermal::Sinter& sinter) {
  const auto& g = sinter.grid();
  const auto& top = sinter.top_height();
  const auto& plane = sinter.top_planes();
  for (std::size_t c = 0; c < g.columns(); ++c) {
    const double h = top.empty() ? g.z_top : top[c];
    const double delta = h - g.z(plane[c]);
    EXPECT_GE(delta, -1e-12 * kDz) << "column " << c;
    if (plane[c] + 1 < g.nz) {
      EXPECT_LT(delta, kDz * (1 + 1e-9)) << "column " << c;
    }
  }
}

}  // namespace

// A block raised 3.3 dz over the plate: its columns' top nodes are three planes up, the rest
// stay on the plate's plane, and the grid holds the planes the block needs.
TEST(GrowingGrid, RaisedColumnsGetPlanesOfTheirOwn) {
  const double lx = 200e-6, ly = 100e-6;
  const thermal::SinterScene scene = plate_scene(lx, ly, 60e-6);
  const std::size_t nx = scene.nodes[0], ny = scene.nodes[1];
  thermal::TopHeight top(nx * ny, 0.0);
  const double lift = 3.3 * kDz;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      if (i > 10 && i + 10 < nx && j > 5 && j + 5 < ny) top[i + nx * j] = lift;
  thermal::Sinter sinter(test::empty_bed(lx, ly, 40e-6), scene, test::table_316l(), top);
  const auto& g = sinter.grid();
  EXPECT_EQ(g.nz_above, 4u);  // ceil(3.3)
  EXPECT_EQ(g.nz, scene.nodes[2] + 4);
  EXPECT_EQ(sinter.top_planes()[15 + nx * 10], g.k_plate() + 3);
  EXPECT_EQ(sinter.top_planes()[2 + nx * 2], g.k_plate());
  expect_thin_top_nodes(sinter);
  const auto r = sinter.run(nullptr, 0, nullptr);
  EXPECT_LT(r.energy.relative_error(), 1e-12);  // round-off: the ledger books every face
  // The empty nodes over the plate beside the block never change.
  const std::size_t empty = g.index(2, 2, g.k_plate() + 1);
  EXPECT_EQ(sinter.substrate_temperature()[empty], scene.initial_temperature);
}

// Every column, the Dirichlet sides too, raised by m whole planes is a plate m dz deeper: the
// raised planes (their own kernel, thickness by thickness) must give what the flat grid's
// kernel gives on the deeper plate, to round-off: same peak on the track's centre line, same
// melt depth from the top, same energy into the reservoir.
TEST(GrowingGrid, WholePlanesRaisedConductAsTheDeeperPlate) {
  const double lx = 200e-6, ly = 120e-6, depth = 60e-6;
  const std::size_t m = 4;
  const double lift = static_cast<double>(m) * kDz;
  const thermal::SinterScene deep = plate_scene(lx, ly, depth + lift);
  thermal::Sinter flat(test::empty_bed(lx, ly, 40e-6), deep, test::table_316l());
  const auto rf = flat.run(nullptr, 0, nullptr);

  const thermal::SinterScene shallow = plate_scene(lx, ly, depth);
  const thermal::TopHeight top(shallow.nodes[0] * shallow.nodes[1], lift);
  thermal::Sinter raised(test::empty_bed(lx, ly, 40e-6), shallow, test::table_316l(), top);
  ASSERT_EQ(raised.grid().nz, flat.grid().nz);
  const auto rr = raised.run(nullptr, 0, nullptr);

  EXPECT_LT(rr.energy.relative_error(), 1e-12);
  EXPECT_NEAR(rr.energy.boundary, rf.energy.boundary, 1e-9 * std::abs(rf.energy.boundary));
  EXPECT_NEAR(rr.max_temperature, rf.max_temperature, 1e-9 * rf.max_temperature);
  ASSERT_EQ(rr.tracks.size(), 1u);
  EXPECT_GT(rf.tracks[0].pool.depth, 2 * kDz) << "the track melts a few nodes deep";
  EXPECT_NEAR(rr.tracks[0].pool.depth, rf.tracks[0].pool.depth, 1e-9);
  EXPECT_NEAR(rr.tracks[0].pool.width, rf.tracks[0].pool.width, 1e-9);
  // Node by node: the raised grid's planes are the deeper plate's.
  const auto& tf = flat.substrate_temperature();
  const auto& tr = raised.substrate_temperature();
  double worst = 0;
  for (std::size_t n = 0; n < tf.size(); ++n) worst = std::max(worst, std::abs(tr[n] - tf[n]));
  EXPECT_LT(worst, 1e-9 * rf.max_temperature);
}
