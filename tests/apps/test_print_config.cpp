// --print-config reads back (docs/hardening.md "Scene files and --print-config"): for every
// program, `X ARGS --print-config` run in one folder and `X --config THAT --print-config` run in
// another print the same text; paths come out absolute, defaults and a material file's values
// commented out, values holding '#', spaces at an end or a line break quoted. And --help prints
// defaults as a scene file writes them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"
#include "run_command.hpp"

namespace {

using powderbed::test::CommandResult;
using powderbed::test::read_text;
using powderbed::test::scratch_dir;

// `app args` run from the folder `dir`, through the shell (args may hold quotes).
CommandResult run_in(const std::string& dir, const std::string& app, const std::string& args) {
  const std::string stem = dir + "/.run";
  const std::string cmd = "cd '" + dir + "' && " + std::string(POWDERBED_APPS_DIR) + "/" + app +
                          " " + args + " >" + stem + ".out 2>" + stem + ".err </dev/null";
  CommandResult r;
  const int raw = std::system(cmd.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_text(stem + ".out");
  r.err = read_text(stem + ".err");
  return r;
}

const std::string kSource = POWDERBED_SOURCE_DIR;

// The round trip of one program: the printed scene, written to A/scene.ini, read back from B.
struct RoundTrip {
  std::string a, b, text;
};

RoundTrip round_trip(const std::string& app, const std::string& args) {
  RoundTrip t{scratch_dir(app + "_a"), scratch_dir(app + "_b"), ""};
  const auto first = run_in(t.a, app, args + " --print-config");
  EXPECT_EQ(first.status, 0) << first.err;
  std::ofstream(t.a + "/scene.ini") << first.out;
  const auto second = run_in(t.b, app, "--config " + t.a + "/scene.ini --print-config");
  EXPECT_EQ(second.status, 0) << second.err;
  EXPECT_EQ(first.out, second.out);
  t.text = first.out;
  return t;
}

bool has_line(const std::string& text, const std::string& line) {
  return ("\n" + text).find("\n" + line + "\n") != std::string::npos;
}

TEST(PrintConfig, PackgenQuotesWhatThePlainFormWouldLose) {
  // A '#', a leading space and a line break: each would change if written plainly.
  const auto t = round_trip("packgen",
                            "--dim 3 --domain 1e-4,1e-4,1e-4 --psd \" mono:d=20e-6\" --seed 3 "
                            "--out 'x#y.h5' --collision \"$(printf 'grid\\n#x')\"");
  EXPECT_TRUE(has_line(t.text, "out = \"" + t.a + "/x#y.h5\"")) << t.text;
  EXPECT_TRUE(has_line(t.text, "psd = \" mono:d=20e-6\"")) << t.text;
  EXPECT_TRUE(has_line(t.text, "collision = \"grid\\n#x\"")) << t.text;
  EXPECT_TRUE(has_line(t.text, "seed = 3")) << t.text;
  EXPECT_TRUE(has_line(t.text, "# approach = 1  (default)")) << t.text;
}

TEST(PrintConfig, DepositMaterialValuesAreNotGiven) {
  const auto t = round_trip("deposit", "--config " + kSource +
                                           "/data/scenes/gz2016-deposit.ini --material 316L "
                                           "--seed 1 --out gz.h5");
  EXPECT_TRUE(has_line(t.text, "material = 316L")) << t.text;
  EXPECT_TRUE(has_line(t.text, "out = " + t.a + "/gz.h5")) << t.text;
  EXPECT_NE(t.text.find("\n# material.density = "), std::string::npos) << t.text;
  EXPECT_NE(t.text.find("  (from --material)\n"), std::string::npos) << t.text;
}

TEST(PrintConfig, SinterSceneRunsFromAnotherFolder) {
  const auto t = round_trip("sinter", "--config " + kSource +
                                          "/data/scenes/gz2016-sinter.ini --bed bed.h5 "
                                          "--out run.h5");
  // The scene's material.table (../materials/316L.csv beside it) is written where it is.
  EXPECT_TRUE(has_line(t.text, "material.table = " + kSource + "/data/materials/316L.csv"))
      << t.text;
  EXPECT_TRUE(has_line(t.text, "bed = " + t.a + "/bed.h5")) << t.text;
  EXPECT_TRUE(has_line(t.text, "# scan.tracks = 0  (default)")) << t.text;
  // The printed scene runs from folder B (a single track: scan.tracks is still a default, not
  // "given without --scan.hatch"; the material file is found).
  powderbed::bed::write_bed_h5(powderbed::bed::simple_cubic_lattice(4, 13.5e-6), t.a + "/bed.h5");
  const auto r = run_in(t.b, "sinter", "--config " + t.a + "/scene.ini --explain");
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST(PrintConfig, KeffPathsAbsolute) {
  const auto t = round_trip("keff", "--config " + kSource +
                                        "/data/scenes/ke2016-steel-1mm.ini --bed ke.h5 "
                                        "--out k.h5 --material 316L");
  EXPECT_TRUE(has_line(t.text, "bed = " + t.a + "/ke.h5")) << t.text;
  EXPECT_TRUE(has_line(t.text, "out = " + t.a + "/k.h5")) << t.text;
}

TEST(PrintConfig, BedstatBedsAndSwitches) {
  const auto t = round_trip("bedstat", "a.h5 'b c.h5' --layer 0,30e-6 --voronoi --spread");
  EXPECT_TRUE(has_line(t.text, "bed = " + t.a + "/a.h5")) << t.text;
  EXPECT_TRUE(has_line(t.text, "bed = " + t.a + "/b c.h5")) << t.text;
  EXPECT_TRUE(has_line(t.text, "voronoi = true")) << t.text;
  EXPECT_TRUE(has_line(t.text, "spread = true")) << t.text;  // a switch here, not build's path
  EXPECT_TRUE(has_line(t.text, "# tol = 1e-06  (default)")) << t.text;
}

TEST(PrintConfig, BedconvPositionalPaths) {
  const auto t = round_trip("bedconv", "in.h5 out.csv");
  EXPECT_TRUE(has_line(t.text, "in = " + t.a + "/in.h5")) << t.text;
  EXPECT_TRUE(has_line(t.text, "out = " + t.a + "/out.csv")) << t.text;
}

TEST(PrintConfig, BuildStageScenesBesideTheBuildScene) {
  const auto t = round_trip("build", "--config " + kSource +
                                         "/data/scenes/build-316L.ini --out run/ --seed 2");
  // Relative in the build scene, they are found beside it and written where they are.
  EXPECT_TRUE(has_line(t.text, "spread = " + kSource + "/data/scenes/spread-blade.ini")) << t.text;
  EXPECT_TRUE(has_line(t.text, "sinter = " + kSource + "/data/scenes/build-316L-scan.ini"))
      << t.text;
  EXPECT_TRUE(has_line(t.text, "out = " + t.a + "/run/")) << t.text;
}

// The scene reader takes quoted values with escapes, and refuses a bad escape or an unclosed
// quote naming the file and the line.
TEST(SceneFile, QuotedValuesAndTheirErrors) {
  const std::string dir = scratch_dir("quoted");
  std::ofstream(dir + "/q.ini") << "dim = 3\ndomain = 1e-4,1e-4,1e-4\nout = o.h5\nseed = 1 # a comment\npsd = \"a\\\\b \\\"c\\\" #d\"  # e\n";
  const auto r = run_in(dir, "packgen", "--config q.ini --print-config");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(has_line(r.out, "psd = \"a\\\\b \\\"c\\\" #d\"")) << r.out;
  EXPECT_TRUE(has_line(r.out, "seed = 1")) << r.out;
  std::ofstream(dir + "/bad.ini") << "dim = 3\npsd = \"a\\qb\"\n";
  const auto bad = run_in(dir, "packgen", "--config bad.ini --print-config");
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(bad.err_lines(), 1) << bad.err;
  EXPECT_NE(bad.err.find("bad.ini:2:"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("unknown escape"), std::string::npos) << bad.err;
  std::ofstream(dir + "/open.ini") << "psd = \"abc\n";
  const auto open = run_in(dir, "packgen", "--config open.ini --print-config");
  EXPECT_EQ(open.status, 2);
  EXPECT_NE(open.err.find("open.ini:1:"), std::string::npos) << open.err;
}

// --help writes a default as a scene file does: the shortest decimal, true/false.
TEST(Help, DefaultsAsTheSceneWritesThem) {
  const auto r = run_in(scratch_dir("help"), "sinter", "--help");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("--spot arg (=5.4e-05)"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("5.3999999999999998e-05"), std::string::npos);
  EXPECT_NE(r.out.find("--effects.wetting arg (=true)"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("arg (=1)\n"), std::string::npos);
}

}  // namespace
