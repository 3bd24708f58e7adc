// End-to-end tests of deposit's spreading mode (recoater.tool): bad tools and supplies exit 2
// with one line; a run stopped after a layer and continued with --in equals the uninterrupted
// one bit for bit; per-layer beds, the tool's force log and the JSON summary.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <utility>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

// A small spread: 30 um spheres, a 1.2 x 0.3 mm strip periodic in y, a blade at 0.5 m/s.
std::string small_scene(const std::string& dir) {
  const std::string path = dir + "/spread.ini";
  std::ofstream f(path);
  f << "psd = mono:d=30e-6\n"
       "domain = 1.5e-3,0.3e-3,0.6e-3\n"
       "periodic = y\n"
       "young-scale = 1e4\n"
       "friction.model = history\n"
       "[recoater]\ntool = blade\nthickness = 100e-6\ngap = 60e-6\nspeed = 0.5\n"
       "start = 0.1e-3\nend = 1.2e-3\nlayer-thickness = 30e-6\n"
       "[supply]\nx0 = 0.16e-3\nx1 = 0.4e-3\nheight = 0.2e-3\ncount = 120\n"
       "[material]\nfriction = 0.5\nrolling = 0.05\n"
       "[effects]\ndrag = false\n";
  return path;
}

}  // namespace

TEST(DepositSpread, BadToolAndSupplyExit2WithOneLine) {
  const std::string dir = test::scratch_dir("spread_bad");
  const std::string base = "--config " + small_scene(dir) + " --seed 1 --out " + dir + "/out.h5 ";
  const std::pair<std::string, std::string> cases[] = {
      {"--recoater.gap 0", "recoater.gap"},
      {"--recoater.gap -1e-6", "recoater.gap"},
      {"--supply.count 100000", "supply.count"},
      {"--supply.x0 0.1e-3", "supply.x0"},
      {"--recoater.tool brush", "recoater.tool"},
      {"--recoater.end 0.05e-3", "recoater.end"},
      {"--t-end 1", "--t-end"},
      {"--supply.volume 1e-12", "supply.count / supply.volume"},
      {"--supply.count 0", "supply.count / supply.volume"},
      {"--supply.dosing 2", "supply.count / supply.volume / supply.dosing"},
      {"--supply.count 0 --supply.dosing 0", "supply.dosing"},
      {"--supply.count 0 --supply.dosing -1", "supply.dosing"},
      {"--supply.count 0 --supply.dosing 2 --supply.bulk-density 1", "supply.bulk-density"},
      {"--periodic x", "--periodic"},
      {"--export-deck yade", "--export-deck"},  // an engine no deck is written for
      // What the decks do not do: keep powder past the end, freeze the deep powder.
      {"--recoater.chamber true --export-deck liggghts", "recoater.chamber"},
      {"--recoater.freeze-depth 100e-6 --export-deck liggghts", "recoater.freeze-depth"},
      {"--recoater.until-rest true --export-deck liggghts", "recoater.until-rest"},
      {"--supply.platform-edge 0.5e-3 --export-deck liggghts", "supply.platform-edge"},
      // The dosing platform under the supply's end or at the tool's end.
      {"--supply.platform-edge 0.3e-3", "supply.platform-edge"},
      {"--supply.platform-edge 1.2e-3", "supply.platform-edge"},
      {"--until-rest", "--until-rest"},  // a drop's; a spread's layers settle by recoater.until-rest
      {"--recoater.until-rest true --recoater.rest-cap 0", "recoater.rest-cap"},
      {"--recoater.until-rest true --rest.speed 0", "rest.speed"},
      // A tool that does not travel pushes the whole supply into the overflow: no layer. Found
      // after the run: --thermo 0 leaves the one line alone, without the run's thermo table.
      {"--recoater.end 0.100001e-3 --recoater.delay 0 --recoater.settle 0 --thermo 0",
       "no powder is left"},
  };
  for (const auto& [args, field] : cases) {
    const auto r = test::run_app("deposit", base + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(field), std::string::npos) << args << ": " << r.err;
  }
  // The blade starting inside the powder of a bed given with --in.
  bed::Bed b;
  b.domain.upper = {1.5e-3, 0.3e-3, 0.6e-3};
  b.domain.periodic = {false, true, false};
  b.add(0.1e-3, 0.15e-3, 0.3e-3, 15e-6);
  bed::write_bed_h5(b, dir + "/in.h5");
  const auto r = test::run_app("deposit", base + "--in " + dir + "/in.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("overlaps particle"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(dir + "/out.h5").good());
}

// supply.dosing d supplies d phi_b (end - start) L_y t of solid a layer, t the first layer's gap
// and then the plate's drop: mono 30 um spheres, so the count is that over one sphere's volume
// (packgen stops at the first sphere that reaches the target: within one).
TEST(DepositSpread, DosingSuppliesTheLayersNominalPowder) {
  const std::string dir = test::scratch_dir("spread_dosing");
  const auto r = test::run_app("deposit", "--config " + small_scene(dir) + " --seed 1 --out " + dir +
                                              "/out.h5 --supply.count 0 --supply.dosing 1.5 "
                                              "--supply.bulk-density 0.1 --layers 2 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const double sphere = 4.0 / 3.0 * M_PI * 15e-6 * 15e-6 * 15e-6;
  const double per_height = 1.5 * 0.1 * (1.2e-3 - 0.1e-3) * 0.3e-3 / sphere;
  const auto layers = r.out.find("\"layers\"");
  ASSERT_NE(layers, std::string::npos) << r.out;
  const std::string first = r.out.substr(layers);
  const std::string second = first.substr(first.find("\"supplied\"") + 1);
  EXPECT_NEAR(test::json_number(first, "supplied"), per_height * 60e-6, 1.0) << r.out;
  EXPECT_NEAR(test::json_number(second, "supplied"), per_height * 30e-6, 1.0) << r.out;
}

TEST(DepositSpread, DropWithHistoryFrictionRunsOnTheEngineWithTheLidAndInsertion) {
  // History friction and rolling resistance need particle rotation: a --t-end drop runs on the
  // engine, the lid and insertion too; what only the drop solver has (RK4) is refused.
  const std::string dir = test::scratch_dir("spread_drop");
  const std::string drop = "--psd mono:d=30e-6 --count 10 --domain 0.3e-3,0.3e-3,0.3e-3 "
                           "--young-scale 1e3 --seed 1 --out " + dir + "/out.h5 ";
  const auto ok = test::run_app("deposit", drop + "--t-end 1e-3 --friction.model history "
                                                  "--material.rolling 0.1 --json");
  ASSERT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.out.find("\"friction_model\":\"history\""), std::string::npos) << ok.out;
  EXPECT_EQ(test::json_number(ok.out, "n"), 10);
  EXPECT_GT(test::json_number(ok.out, "steps"), 0);
  const auto lid = test::run_app("deposit", drop + "--t-end 1e-3 --friction.model history --lid "
                                                   "--lid.travel 1e-4 --lid.relax 1e-4 --thermo 0 --json");
  ASSERT_EQ(lid.status, 0) << lid.err;
  EXPECT_NE(lid.out.find("\"stopped_by\":\"travel\""), std::string::npos) << lid.out;
  const auto inserted = test::run_app("deposit", drop + "--t-end 1e-3 --friction.model history --insert.enabled "
                                                        "true --insert.rate 1e5 --thermo 0 --json");
  ASSERT_EQ(inserted.status, 0) << inserted.err;
  EXPECT_EQ(test::json_number(inserted.out, "inserted"), 10) << inserted.out;
  for (const auto& [args, field] :
       {std::pair{"--t-end 1e-3 --integrator rk4 --friction.model history", "friction.model"},
        std::pair{"--t-end 1e-3 --integrator rk4 --material.rolling 0.1", "material.rolling"},
        std::pair{"--t-end 1e-3 --friction.model static", "friction.model"}}) {
    const auto r = test::run_app("deposit", drop + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(field), std::string::npos) << args << ": " << r.err;
  }
}

TEST(DepositSpread, ContinuedRunEqualsTheUninterruptedOneBitForBit) {
  const std::string dir = test::scratch_dir("spread_continue");
  const std::string scene = "--config " + small_scene(dir) + " --seed 3 ";
  const auto whole = test::run_app("deposit", scene + "--layers 2 --json --out " + dir + "/A.h5 " +
                                                  "--tool-forces " + dir + "/forces.csv");
  ASSERT_EQ(whole.status, 0) << whole.err;
  EXPECT_EQ(test::json_number(whole.out, "layers_done"), 2);
  EXPECT_EQ(test::json_number(whole.out, "lost"), 0);
  // Two supplies of 120, none lost: in the bed or removed past the tool's end.
  const double overflow = test::json_number(whole.out, "overflow");  // layer 1's
  EXPECT_GT(overflow, 0);
  EXPECT_LT(test::json_number(whole.out, "n"), 240 - overflow);
  const auto first = test::run_app("deposit", scene + "--out " + dir + "/B.h5");
  ASSERT_EQ(first.status, 0) << first.err;
  const auto next = test::run_app("deposit", scene + "--in " + dir + "/B.h5 --out " + dir + "/C.h5");
  ASSERT_EQ(next.status, 0) << next.err;
  const bed::Bed a = bed::read_bed_h5(dir + "/A.h5");
  const bed::Bed a2 = bed::read_bed_h5(dir + "/A-002.h5");  // the per-layer bed of layer 2
  const bed::Bed c = bed::read_bed_h5(dir + "/C.h5");
  ASSERT_EQ(a.n(), c.n());
  EXPECT_EQ(a.x, c.x);
  EXPECT_EQ(a.y, c.y);
  EXPECT_EQ(a.z, c.z);
  EXPECT_EQ(a.vx, c.vx);
  EXPECT_EQ(a.vz, c.vz);
  EXPECT_EQ(a.id, c.id);
  EXPECT_EQ(a.x, a2.x);
  // The force log: a header and rows of layer 1 then 2.
  std::ifstream forces(dir + "/forces.csv");
  std::string header, row, last;
  std::getline(forces, header);
  EXPECT_EQ(header, "layer,time,x,fx,fy,fz");
  while (std::getline(forces, row)) last = row;
  EXPECT_EQ(last.substr(0, 2), "2,");
}
