// End-to-end tests of build (docs/build.md): bad input exits 2 with one line before any layer is
// spread; a build stopped after layer 2 and continued with --in equals the uninterrupted one bit
// for bit; the per-layer files and the report.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/dem/spread.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

// The small build (tests/data/build-small/): 120 spheres of 30 um spread by a blade over a
// 1.5 x 0.3 mm strip, two tracks of 100 W at 1 m/s (Beer-Lambert, 20 um grid) behind the supply.
const std::string kScenes = std::string(POWDERBED_TEST_DATA) + "/build-small";
const std::string kConfig = kScenes + "/build.ini";

}  // namespace

TEST(BuildCli, BadInputExits2WithOneLineAndWritesNothing) {
  const std::string dir = test::scratch_dir("build_bad");
  const std::string config = kConfig;
  std::ofstream(dir + "/off.csv") << "x0,y0,x1,y1,power,speed\n0.5e-3,0.1e-3,2.5e-3,0.1e-3,100,1\n";
  std::ofstream(dir + "/drop.ini") << "psd = mono:d=30e-6\ndomain = 1e-3,1e-3,1e-3\ncount = 10\n";
  std::filesystem::create_directories(dir + "/full");
  std::ofstream(dir + "/full/keep.txt") << "a user's file\n";
  const std::string out = " --out " + dir + "/run";
  const std::pair<std::string, std::string> cases[] = {
      {"--layers 0" + out, "--layers"},
      // The box (0.6 mm, gap 60 um, 30 um layers) holds 18 layers; a count that would wrap
      // past the last layer number is refused the same way.
      {"--layers 19" + out, "--layers"},
      {"--layers 18446744073709551615" + out, "--layers"},
      {"--sinter-args '--scan.hatch 0'" + out, "scan.hatch"},
      {"--sinter-args '--scan.hatch -1e-6'" + out, "scan.hatch"},
      {"--sinter " + kScenes + "/scan-track.ini --sinter-args '--scan-path " + dir + "/off.csv'" + out,
       "scan"},
      {"--spread " + dir + "/drop.ini" + out, "--spread"},
      {"--spread-args '--recoater.gap 0'" + out, "recoater.gap"},
      {"--out " + dir + "/full", "--out"},
      {"--in " + dir + "/missing.h5" + out, "--in"},
  };
  for (const auto& [args, field] : cases) {
    const auto r = test::run_app("build", "--config " + config + " " + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(field), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/run")) << args;
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/full/keep.txt"));
}

TEST(BuildCli, ContinuedBuildEqualsTheUninterruptedOneBitForBit) {
  const std::string dir = test::scratch_dir("build_restart");
  const std::string config = kConfig;
  const auto whole = test::run_app("build", "--config " + config + " --layers 3 --threads 2 --json --out " + dir + "/whole");
  ASSERT_EQ(whole.status, 0) << whole.err;
  const auto first = test::run_app("build", "--config " + config + " --layers 2 --threads 1 --out " + dir + "/first");
  ASSERT_EQ(first.status, 0) << first.err;
  const auto rest = test::run_app("build", "--config " + config + " --layers 1 --in " + dir +
                                               "/first/layer-002.h5 --out " + dir + "/rest");
  ASSERT_EQ(rest.status, 0) << rest.err;
  // Every layer's files, and the report's layers.
  for (const char* f : {"layer-001.h5", "layer-001-spread.h5", "layer-001-scan.h5",
                        "layer-001-scan.xmf", "layer-003.h5", "build.json"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/whole/" + f)) << f;
  EXPECT_NE(whole.out.find("\"lack_of_fusion\""), std::string::npos) << whole.out;
  EXPECT_NE(whole.out.find("\"layer\":3"), std::string::npos) << whole.out;
  const std::string a = dir + "/whole/layer-003.h5", b = dir + "/rest/layer-003.h5";
  const bed::Bed ba = bed::read_bed_h5(a), bb = bed::read_bed_h5(b);
  ASSERT_EQ(ba.n(), bb.n());
  ASSERT_GT(ba.n(), 0u);
  EXPECT_EQ(ba.x, bb.x);
  EXPECT_EQ(ba.y, bb.y);
  EXPECT_EQ(ba.z, bb.z);
  EXPECT_EQ(ba.vz, bb.vz);
  EXPECT_EQ(ba.id, bb.id);
  const dem::SpreadState sa = dem::read_spread_state(a, ba), sb = dem::read_spread_state(b, bb);
  EXPECT_EQ(sa.layers_done, 3u);
  EXPECT_EQ(sa.step, sb.step);
  EXPECT_FALSE(sa.floor.empty());
  EXPECT_EQ(sa.floor.z, sb.floor.z);
  EXPECT_EQ(sa.pair_history, sb.pair_history);
  EXPECT_EQ(sa.wall_history, sb.wall_history);
}
