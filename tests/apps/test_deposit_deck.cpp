// deposit --export-deck (docs/decks.md): the settled bed as a LAMMPS data file and an input deck
// with the run's laws and time step beside --out; an engine or a scene a deck cannot take exits 2
// before the run, writing nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <vector>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/deck.hpp"
#include "powderbed/bed/io.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

// Two 20 um particles resting 1 um above the floor of a 0.3 mm box, periodic in y.
std::string resting_pair(const std::string& dir) {
  bed::Bed b;
  b.domain.upper = {0.3e-3, 0.3e-3, 0.3e-3};
  b.domain.periodic = {false, true, false};
  b.add(1e-4, 1.5e-4, 21e-6, 20e-6);
  b.add(2e-4, 1.5e-4, 21e-6, 20e-6);
  const std::string path = dir + "/in.h5";
  bed::write_bed_h5(b, path);
  return path;
}

TEST(DepositDeck, WritesTheRunsDeckBesideTheBed) {
  const std::string dir = test::scratch_dir("deposit_deck");
  const auto r = test::run_app("deposit", "--in " + resting_pair(dir) + " --t-end 1e-6 --dt 1e-9 "
                               "--material.density 8190 --seed 1 --out " + dir + "/bed.h5 "
                               "--export-deck liggghts");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string deck = test::read_text(dir + "/in.bed.liggghts");
  EXPECT_NE(deck.find("timestep       1.0000000000000001e-09"), std::string::npos) << deck;
  EXPECT_NE(deck.find("boundary       f p f"), std::string::npos);
  EXPECT_NE(deck.find("the deposit run that wrote " + dir + "/bed.h5"), std::string::npos);
  // The bed as settled, with the run's velocities and density.
  const bed::Bed data = bed::read_lammps_data(dir + "/bed.data");
  const bed::Bed settled = bed::read_bed_h5(dir + "/bed.h5");
  EXPECT_EQ(data.z, settled.z);
  EXPECT_EQ(data.vz, settled.vz);
  EXPECT_EQ(data.domain.periodic, settled.domain.periodic);
  EXPECT_NE(test::read_text(dir + "/bed.data").find(" 8190 "), std::string::npos);
}

TEST(DepositDeck, AnEngineOrZetaItCannotTakeExits2BeforeTheRun) {
  const std::string dir = test::scratch_dir("deposit_deck_bad");
  const std::string in = resting_pair(dir);
  auto r = test::run_app("deposit", "--in " + in + " --t-end 1e-6 --seed 1 --out " + dir +
                                        "/bed.h5 --export-deck yade");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--export-deck: 'yade'"), std::string::npos) << r.err;
  // LAMMPS's tsuji damping reaches zeta 0.5196 at most (docs/decks.md).
  r = test::run_app("deposit", "--in " + in + " --t-end 1e-6 --seed 1 --material.damping 0.8 "
                               "--out " + dir + "/bed.h5 --export-deck lammps");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("zeta 0.8"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bed.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/bed.data"));
}

}  // namespace

namespace {

// The vertices of an ASCII STL.
std::vector<std::array<double, 3>> stl_vertices(const std::string& path) {
  std::istringstream in(test::read_text(path));
  std::vector<std::array<double, 3>> v;
  for (std::string word; in >> word;) {
    if (word != "vertex") continue;
    std::array<double, 3> p{};
    in >> p[0] >> p[1] >> p[2];
    v.push_back(p);
  }
  return v;
}

const std::string kSpreadScene = std::string(POWDERBED_TEST_DATA) + "/spread-liggghts/spread.ini";

}  // namespace

TEST(DepositDeck, SpreadWritesTheToolTheSupplyAndTheLayerLoop) {
  const std::string dir = test::scratch_dir("deposit_spread_deck");
  const auto r = test::run_app("deposit", "--config " + kSpreadScene + " --seed 1 --layers 3 --out " +
                                              dir + "/L.h5 --export-deck liggghts");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/L.h5"));  // the deck instead of the spread
  // The first layer's supply as deposit places it: 600 particles in the supply region.
  const bed::Bed supply = bed::read_lammps_data(dir + "/L.data");
  ASSERT_EQ(supply.n(), 600u);
  for (std::size_t i = 0; i < supply.n(); ++i) {
    EXPECT_GE(supply.x[i] - supply.radius[i], 0.16e-3 - 1e-12);
    EXPECT_LE(supply.x[i] + supply.radius[i], 0.56e-3 + 1e-12);
  }
  // The blade: 100 um thick about x = 0.1 mm, its bottom at the 90 um gap, inset across y.
  double x0 = 1, x1 = -1, z0 = 1, y0 = 1, y1 = -1;
  for (const auto& p : stl_vertices(dir + "/L.tool.stl")) {
    x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), z0 = std::min(z0, p[2]);
    y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
  }
  EXPECT_NEAR(x0, 0.05e-3, 1e-15);
  EXPECT_NEAR(x1, 0.15e-3, 1e-15);
  EXPECT_EQ(z0, 90e-6);
  EXPECT_GT(y0, 0.0);
  EXPECT_LT(y1, 0.3e-3);
  const std::string deck = test::read_text(dir + "/in.L.liggghts");
  for (const char* line : {"fix            tool all mesh/surface file L.tool.stl type 2 move 0 0 ${RAISE}",
                           "fix            push all move/mesh mesh tool linear 0.20000000000000001 0 0",
                           "variable       NLAYERS index 3", "fix            move all nve/sphere",
                           "pair_style     gran model hertz tangential history rolling_friction epsd",
                           "particles_in_region 600", "delete_atoms   region overflow${L}",
                           "jump           SELF layer"})
    EXPECT_NE(deck.find(line), std::string::npos) << line << "\n" << deck;
}

// LAMMPS: the blade a region block moved by a step variable under fix wall/gran/region, the floor
// the box's zplane wall, the supply of later layers by fix pour, the same layer dumps' names.
TEST(DepositDeck, SpreadToLammpsMovesARegionWall) {
  const std::string dir = test::scratch_dir("deposit_spread_lammps");
  const auto r = test::run_app("deposit", "--config " + kSpreadScene + " --seed 1 --layers 3 --out " +
                                              dir + "/L.h5 --export-deck lammps");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/L.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/L.tool.stl"));  // no mesh: a region
  EXPECT_EQ(bed::read_lammps_data(dir + "/L.data").n(), 600u);
  const std::string deck = test::read_text(dir + "/in.L.lammps");
  for (const char* line :
       {"region         tool block 5.0000000000000002e-05 0.00015000000000000001 INF INF "
        "$(9.0000000000000006e-05+v_RAISE) INF side out units box move v_TX NULL NULL",
        "fix            tool_wall all wall/gran/region granular hertz ", " region tool\n",
        "tangential mindlin ", " rolling sds ", "fix            wall_z all wall/gran granular hertz ",
        "  run            16496  # recoater.delay", "  run            22682  # the travel",
        "variable       TX equal (step<${S1})*4.8498041729800489e-08*v_MOVED+(step>=${S1})*0.0010999999999999998",
        "fix supply all pour 600 1 ", "variable       LAYER_DUMP index L.lammps.layer",
        "write_dump     all custom ${LAYER_DUMP}-${L}.lammpstrj", "delete_atoms   region overflow",
        "region         tool delete", "variable       NLAYERS index 3", "jump           SELF layer"})
    EXPECT_NE(deck.find(line), std::string::npos) << line << "\n" << deck;
  EXPECT_EQ(bed::spread_layer_dump(dir + "/L.data", 2, bed::DeckEngine::lammps), dir + "/L.lammps.layer-2.lammpstrj");
}

// The roller: a cylinder along y through its axis, turned by `rotate` at omega while it travels.
TEST(DepositDeck, LammpsRollerIsARotatingCylinderRegion) {
  const std::string dir = test::scratch_dir("deposit_roller_lammps");
  const auto r = test::run_app("deposit", "--config " + kSpreadScene + " --seed 1 --out " + dir +
                               "/R.h5 --recoater.tool roller --recoater.radius 0.1e-3 --recoater.omega -200 "
                               "--supply.x0 0.2e-3 --supply.x1 0.6e-3 --export-deck lammps");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string deck = test::read_text(dir + "/in.R.lammps");
  EXPECT_NE(deck.find("region         tool cylinder y 0.0001 $(0.00019000000000000001+v_RAISE) 0.0001 INF INF "
                      "side out units box move v_TX NULL NULL rotate v_SPIN 0.0001 0.00014999999999999999 "
                      "$(0.00019000000000000001+v_RAISE) 0 1 0"),
            std::string::npos)
      << deck;
  // -200 rad/s times the step
  EXPECT_NE(deck.find("variable       SPIN equal -4.8498041729800"), std::string::npos) << deck;
}

// What the LAMMPS deck cannot take exits 2 with one line naming the engine that can, nothing written.
TEST(DepositDeck, LammpsRefusesARoundedBlade) {
  const std::string dir = test::scratch_dir("deposit_rounded_lammps");
  const auto l = test::run_app("deposit", "--config " + kSpreadScene + " --seed 1 --out " + dir +
                                              "/M.h5 --recoater.edge-radius 10e-6 --export-deck lammps");
  EXPECT_EQ(l.status, 2);
  EXPECT_EQ(l.err_lines(), 1) << l.err;
  EXPECT_NE(l.err.find("recoater.edge-radius"), std::string::npos) << l.err;
  EXPECT_NE(l.err.find("liggghts"), std::string::npos) << l.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/M.data"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/in.M.lammps"));
}

TEST(DepositDeck, RollerIsACylinderOfItsRadiusAboveTheGap) {
  const std::string dir = test::scratch_dir("deposit_roller_deck");
  const auto r = test::run_app("deposit", "--config " + kSpreadScene + " --seed 1 --out " + dir +
                               "/R.h5 --recoater.tool roller --recoater.radius 0.1e-3 "
                               "--recoater.omega -200 --recoater.start 0.1e-3 --supply.x0 0.2e-3 --supply.x1 0.6e-3 "
                               "--export-deck liggghts");
  ASSERT_EQ(r.status, 0) << r.err;
  double lowest = 1;
  for (const auto& p : stl_vertices(dir + "/R.tool.stl")) {
    lowest = std::min(lowest, p[2]);
    // on the circle about the axis (x = start, z = gap + R)
    const double d = std::hypot(p[0] - 0.1e-3, p[2] - (90e-6 + 0.1e-3));
    EXPECT_NEAR(d, 0.1e-3, 1e-15) << p[0] << " " << p[2];
  }
  EXPECT_NEAR(lowest, 90e-6, 1e-18);
  EXPECT_NE(test::read_text(dir + "/in.R.liggghts").find("rotate origin"), std::string::npos);
}
