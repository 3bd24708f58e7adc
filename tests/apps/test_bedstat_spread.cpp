// End-to-end tests of bedstat --spread (docs/spread-layer.md): the "spread" JSON object on a
// lattice with closed-form layer statistics, the gap and the feed taken from what the bed records,
// the height-map CSV, and bad input (exit 2, one line, nothing written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"
#include "run_command.hpp"

namespace {

using powderbed::test::json_number;
using powderbed::test::run_app;
using std::numbers::pi;

constexpr double kRadius = 1e-5;

class BedstatSpreadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = powderbed::test::scratch_dir("bedstat_spread");
    // 10^3 simple cubic touching spheres on the floor z = 0: the layer [0, 1.5 r] holds caps of
    // height 1.5 r of the bottom row (100 centres at z = r), and the top view sees that row only
    // (the next row's bottoms are at 2 r, above the layer).
    powderbed::bed::Bed b = powderbed::bed::simple_cubic_lattice(10, kRadius);
    powderbed::bed::write_bed_h5(b, plain());
    b.provenance.scene = "psd = mono:r=1e-5\nrecoater.gap = 1.5e-05\nrecoater.tool = blade\n";
    powderbed::bed::write_bed_h5(b, recorded());
  }
  std::string plain() const { return dir_ + "/sc.h5"; }
  std::string recorded() const { return dir_ + "/sc-recorded.h5"; }
  std::string dir_;
};

// Cap of height h = 1.5 r per 2r x 2r cell: pi h^2 (3r - h) / 3 / (4 r^2 h) = 3 pi / 16.
constexpr double kLayerDensity = 3 * pi / 16;

TEST_F(BedstatSpreadTest, JsonOfTheBottomRowMatchesClosedForms) {
  const auto r = run_app("bedstat", plain() + " --spread --gap 1.5e-5 --raster 2e-7 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_NE(r.out.find("\"spread\":{"), std::string::npos) << r.out;
  // Exact caps: rounding only.
  EXPECT_NEAR(json_number(r.out, "density"), kLayerDensity, 1e-9);
  // The square monolayer at raster r/50: within 0.2 % of the closed forms
  // (tests/bed/test_stats_layer.cpp); 0.5 %.
  EXPECT_NEAR(json_number(r.out, "coverage"), pi / 4, 5e-3 * pi / 4);
  const double mean = 5 * pi * kRadius / 12;
  EXPECT_NEAR(json_number(r.out, "mean_height"), mean, 5e-3 * mean);
  EXPECT_EQ(json_number(r.out, "particles"), 100);
  EXPECT_EQ(json_number(r.out, "gap"), 1.5e-5);
  // Equal spheres: no trend along x; no feed recorded or given: no KS.
  EXPECT_NEAR(json_number(r.out, "slope"), 0.0, 1e-12);
  EXPECT_EQ(r.out.find("psd_ks"), std::string::npos) << r.out;
}

TEST_F(BedstatSpreadTest, GapAndFeedComeFromTheBedsRecord) {
  const auto r = run_app("bedstat", recorded() + " --spread --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_number(r.out, "gap"), 1.5e-5);
  EXPECT_NE(r.out.find("\"gap_source\":\"recoater.gap of the bed\""), std::string::npos) << r.out;
  EXPECT_NEAR(json_number(r.out, "density"), kLayerDensity, 1e-9);
  // All radii are the recorded mono PSD's: D = 0, p = 1.
  EXPECT_NE(r.out.find("\"psd_ks\":{\"feed\":\"mono:r=1e-5\""), std::string::npos) << r.out;
  EXPECT_NEAR(json_number(r.out, "d"), 0.0, 1e-12);
  EXPECT_EQ(json_number(r.out, "p"), 1.0);
  // --gap wins over the record; --feed over the recorded PSD (the bed against itself: D = 0).
  const auto g = run_app("bedstat", recorded() + " --spread --gap 5e-6 --feed " + plain() + " --json");
  ASSERT_EQ(g.status, 0) << g.err;
  EXPECT_EQ(json_number(g.out, "gap"), 5e-6);
  EXPECT_EQ(json_number(g.out, "n_feed"), 1000);
  EXPECT_NEAR(json_number(g.out, "d"), 0.0, 1e-12);
}

TEST_F(BedstatSpreadTest, TableAndHeightMap) {
  const std::string csv = dir_ + "/map.csv";
  const auto r = run_app("bedstat", plain() + " --spread --gap 1.5e-5 --raster 1e-6 --height-map " + csv);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("spread: layer density"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.589049"), std::string::npos) << r.out;  // 3 pi / 16
  // 200 x 200 cells of 1 um over the 0.2 mm square, a header line, x fastest.
  const std::string text = powderbed::test::read_text(csv);
  EXPECT_EQ(text.rfind("x,y,height,covered\n", 0), 0u);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 200 * 200 + 1);
}

TEST_F(BedstatSpreadTest, BadInputIsExit2WithOneLineAndNothingWritten) {
  const std::string csv = dir_ + "/bad.csv";
  const std::string cases[] = {
      plain() + " --spread",                       // no gap given or recorded
      plain() + " --spread --gap 0",               // gap <= 0
      plain() + " --spread --gap 1e-5 --window 1,2",  // window outside the domain
      plain() + " --spread --gap 1e-5 --raster -1",
      plain() + " --spread --gap 1e-5 --segregation-bins 0",
      plain() + " --gap 1e-5",                     // a --spread option without --spread
      plain() + " " + recorded() + " --spread --gap 1e-5",  // fine, but then:
  };
  for (std::size_t k = 0; k + 1 < std::size(cases); ++k) {
    const auto r = run_app("bedstat", cases[k] + " --height-map " + csv);
    EXPECT_EQ(r.status, 2) << cases[k] << ": " << r.out;
    EXPECT_EQ(r.err_lines(), 1) << cases[k] << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(csv)) << cases[k];
  }
  // A height map of two beds: refused.
  const auto two = run_app("bedstat", cases[std::size(cases) - 1] + " --height-map " + csv);
  EXPECT_EQ(two.status, 2);
  EXPECT_EQ(two.err_lines(), 1) << two.err;
  EXPECT_FALSE(std::filesystem::exists(csv));
  // A height map that is not CSV.
  const auto ext = run_app("bedstat", plain() + " --spread --gap 1e-5 --height-map " + dir_ + "/m.h5");
  EXPECT_EQ(ext.status, 2);
  EXPECT_EQ(ext.err_lines(), 1) << ext.err;
}

}  // namespace
