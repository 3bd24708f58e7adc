// build --spread-engine liggghts [--mpi N] (docs/build.md "Spreading in LIGGGHTS"): a bad engine,
// rank count or a missing liggghts exits 2 with one line before layer 1; with LIGGGHTS and
// mpirun installed, two layers of the small build spread on 2 ranks (the second on the fused
// solid of the first, as a floor STL) and feed the scan. The layer statistics against deposit's
// engine: ctest decks.spread_liggghts.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/dem/spread.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

const std::string kConfig = std::string(POWDERBED_TEST_DATA) + "/build-small/build.ini";

bool installed(const char* program) {
  return std::system((std::string("command -v ") + program + " >/dev/null 2>&1").c_str()) == 0;
}

// Sets PATH for the programs the test runs, and puts it back.
struct PathFor {
  std::string old;
  explicit PathFor(const std::string& path) : old(std::getenv("PATH") ? std::getenv("PATH") : "") {
    ::setenv("PATH", path.c_str(), 1);
  }
  ~PathFor() { ::setenv("PATH", old.c_str(), 1); }
};

}  // namespace

TEST(BuildLiggghts, BadEngineOrMissingLiggghtsExits2WithOneLine) {
  const std::string dir = test::scratch_dir("build_liggghts_bad");
  const std::string out = " --out " + dir + "/run";
  const std::pair<std::string, std::string> cases[] = {
      {"--spread-engine yade", "--spread-engine: 'yade'"},
      {"--spread-engine liggghts --mpi 0", "--mpi: 0"},
      {"--mpi 2", "--mpi: given with --spread-engine deposit"},
      {"--spread-args '--export-deck liggghts'", "'--export-deck' is set by the build itself"},
      {"--spread-engine liggghts --spread-args '--recoater.until-rest true'", "recoater.until-rest: true"},
      {"--spread-engine liggghts --spread-args '--sleep.on true'", "sleep.on: true"},
  };
  for (const auto& [args, field] : cases) {
    const auto r = test::run_app("build", "--config " + kConfig + " " + args + out);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(field), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/run")) << args;
  }
  // A PATH with coreutils' timeout (which runs the program) and no liggghts or mpirun.
  std::filesystem::create_directories(dir + "/bin");
  std::filesystem::create_symlink("/usr/bin/timeout", dir + "/bin/timeout");
  PathFor path(dir + "/bin");
  for (const std::string args : {"--spread-engine liggghts", "--spread-engine liggghts --mpi 2"}) {
    const auto r = test::run_app("build", "--config " + kConfig + " " + args + out);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find("no `liggghts` on PATH"), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/run")) << args;
  }
}

TEST(BuildLiggghts, TwoLayersSpreadOnTwoRanksFeedTheScan) {
  if (!installed("liggghts") || !installed("mpirun"))
    GTEST_SKIP() << "liggghts or mpirun not installed (apt-get install liggghts openmpi-bin)";
  const std::string dir = test::scratch_dir("build_liggghts");
  const auto r = test::run_app("build", "--config " + kConfig + " --layers 2 --spread-engine liggghts "
                               "--mpi 2 --json --out " + dir + "/run");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(test::json_number(r.out, "layers_done"), 2) << r.out;
  for (const char* layer : {"001", "002"}) {
    const std::string spread = dir + "/run/layer-" + layer + "-spread.h5";
    const bed::Bed b = bed::read_bed_h5(spread);
    // deposit's engine leaves 56 and 99 of the supplies on this scene; the layer is LIGGGHTS's
    EXPECT_GT(b.n(), 30u) << spread;
    for (std::size_t i = 0; i < b.n(); ++i) EXPECT_LT(b.z[i], 0.6e-3) << spread;
    EXPECT_TRUE(std::filesystem::exists(dir + "/run/liggghts-" + layer + "/log.liggghts"));
    EXPECT_TRUE(dem::has_spread_state(dir + "/run/layer-" + layer + ".h5"));
  }
  // Layer 2 spreads on what layer 1 fused: the floor goes to LIGGGHTS as an STL.
  EXPECT_FALSE(std::filesystem::exists(dir + "/run/liggghts-001/spread.floor.stl"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/run/liggghts-002/spread.floor.stl"));
  EXPECT_NE(test::read_text(dir + "/run/liggghts-002/in.spread.liggghts").find("meshes floor tool"),
            std::string::npos);
}
