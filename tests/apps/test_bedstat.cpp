// End-to-end tests of bedstat: JSON keys and values on a lattice with closed-form statistics,
// the side-by-side table, and bad input (exit 2, one line).
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <sstream>
#include <vector>
#include <numbers>

#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"
#include "run_command.hpp"

using powderbed::test::json_number;

namespace {

using powderbed::test::run_app;

// Pulls a top-level number out of the one-line JSON object (keys are unique in our output).
class BedstatTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = powderbed::test::scratch_dir("bedstat");
    // 10^3 simple cubic touching spheres: phi = pi/6, Z = 2 * 2700 / 1000 = 5.4.
    powderbed::bed::write_bed_h5(powderbed::bed::simple_cubic_lattice(10, 1e-5), sc_path());
  }
  std::string sc_path() const { return dir_ + "/sc.h5"; }
  std::string dir_;
};

TEST_F(BedstatTest, JsonOfSimpleCubicLatticeMatchesClosedForms) {
  const auto r = run_app("bedstat", sc_path() + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  // Exact lattice: only rounding of positions (~1e-16 relative) separates these from closed form.
  // One shape for any number of beds: {"beds": [{...}]}.
  EXPECT_EQ(r.out.rfind("{\"beds\":[{", 0), 0u) << r.out;
  EXPECT_NEAR(json_number(r.out, "box_density"), std::numbers::pi / 6, 1e-9);
  EXPECT_NEAR(json_number(r.out, "coordination"), 5.4, 1e-12);
  EXPECT_EQ(json_number(r.out, "n"), 1000);
  EXPECT_EQ(json_number(r.out, "dimension"), 3);
  EXPECT_EQ(json_number(r.out, "rattlers"), 0);
  EXPECT_NEAR(json_number(r.out, "max_overlap"), 0.0, 1e-12);
  for (const char* key : {"\"1e-06\":", "\"0.001\":", "\"0.01\":"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " missing in " << r.out;
  }
}

TEST_F(BedstatTest, LayerDensityOfOneLatticeRow) {
  // The layer z in [0, 2r] holds one full row of spheres: phi = pi/6 as well; the half layer
  // [0, r] holds hemispheres: also pi/6 by symmetry.
  const auto r = run_app("bedstat", sc_path() + " --json --layer 0,1e-5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NEAR(json_number(r.out, "layer_density"), std::numbers::pi / 6, 1e-9);
  // Named for what it is: no bare "density" that means the layer's with --layer.
  EXPECT_EQ(r.out.find("\"density\":"), std::string::npos) << r.out;
}

TEST_F(BedstatTest, TwoBedsPrintSideBySide) {
  const std::string fcc = dir_ + "/fcc.h5";
  powderbed::bed::write_bed_h5(powderbed::bed::fcc_lattice(4, 1e-5), fcc);
  const auto r = run_app("bedstat", sc_path() + " " + fcc);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("sc.h5"), std::string::npos);
  EXPECT_NE(r.out.find("fcc.h5"), std::string::npos);
  EXPECT_NE(r.out.find("0.523599"), std::string::npos) << r.out;  // pi/6
  EXPECT_NE(r.out.find("0.74048"), std::string::npos) << r.out;   // pi/(3 sqrt 2)
}

// Two long bed names (longer than the 16-character columns) stay two words in the header row:
// each column is as wide as its widest cell plus two spaces.
TEST_F(BedstatTest, LongBedNamesNeverRunTogether) {
  const std::string a = dir_ + "/gz-lammps-final-snapshot-of-the-run.h5";
  const std::string b = dir_ + "/gz-deposit-final-snapshot-of-the-run.h5";
  powderbed::bed::write_bed_h5(powderbed::bed::simple_cubic_lattice(3, 1e-5), a);
  powderbed::bed::write_bed_h5(powderbed::bed::fcc_lattice(2, 1e-5), b);
  const auto r = run_app("bedstat", a + " " + b);
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream lines(r.out);
  std::string header;
  std::getline(lines, header);
  std::istringstream words(header);
  std::vector<std::string> cells{std::istream_iterator<std::string>(words), {}};
  ASSERT_EQ(cells.size(), 3u) << header;
  EXPECT_EQ(cells[1], "gz-lammps-final-snapshot-of-the-run.h5");
  EXPECT_EQ(cells[2], "gz-deposit-final-snapshot-of-the-run.h5");
  // Every row lines up with the header: the cells end at the same column.
  for (std::string line; std::getline(lines, line);) EXPECT_EQ(line.size(), header.size()) << line;
}

// A particle resting on the floor or against a wall, with no particle contact, is not a rattler;
// only the one touching nothing is, and the table's label says which count it is.
TEST_F(BedstatTest, ParticlesOnTheFloorAreNotRattlers) {
  powderbed::bed::Bed bed;
  bed.domain.upper = {1e-3, 1e-3, 1e-3};
  bed.add(5e-4, 5e-4, 1e-5, 1e-5);  // on the floor
  bed.add(1e-5, 2e-4, 5e-4, 1e-5);  // against the wall x = 0
  bed.add(5e-4, 5e-4, 5e-4, 1e-5);  // floating
  const std::string path = dir_ + "/floor.h5";
  powderbed::bed::write_bed_h5(bed, path);
  const auto json = run_app("bedstat", path + " --json");
  ASSERT_EQ(json.status, 0) << json.err;
  EXPECT_EQ(json_number(json.out, "rattlers"), 1) << json.out;
  const auto table = run_app("bedstat", path);
  ASSERT_EQ(table.status, 0) << table.err;
  EXPECT_NE(table.out.find("rattlers (no particle/wall) (tol 1e-06)"), std::string::npos)
      << table.out;
}

TEST_F(BedstatTest, RadiusHistogramAgainstTargetPsd) {
  // All 1000 radii are 1e-5: one bin holds them all, and a mono target puts all 1000 there too.
  const auto r = run_app("bedstat", sc_path() + " --json --histogram 4 --psd mono:r=1e-5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"radius_histogram\":{\"edges\":["), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"target\":["), std::string::npos) << r.out;
  EXPECT_NEAR(json_number(r.out, "ks_distance"), 0.0, 1e-12);
}

TEST_F(BedstatTest, MissingFileIsExit2WithOneLine) {
  const auto r = run_app("bedstat", dir_ + "/nope.h5 --json");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("nope.h5"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(BedstatTest, ReversedLayerIsExit2WithOneLine) {
  const auto r = run_app("bedstat", sc_path() + " --layer 2e-5,1e-5");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--layer"), std::string::npos) << r.err;
}

TEST_F(BedstatTest, MalformedPsdIsExit2WithOneLine) {
  const auto r = run_app("bedstat", sc_path() + " --psd gauss:mean=1e-5,sd=1e-6,min=2e-5,max=1e-5");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--psd"), std::string::npos) << r.err;
}

}  // namespace

TEST_F(BedstatTest, DiameterQuantilesOnBothBases) {
  // Nine 10 um particles and one 30 um one. By number D10 = D50 = D90 = 10 um (9 of 10 are
  // small); by volume the big one holds 27 of the 36 volume units, so D10 = 10 um (the small ones
  // reach 0.25 of the volume) and D50 = D90 = 30 um.
  powderbed::bed::Bed b;
  b.domain.upper = {4e-4, 4e-4, 4e-4};
  for (int i = 0; i < 9; ++i) b.add(2e-5 + 3e-5 * i, 2e-5, 2e-5, 5e-6);
  b.add(2e-4, 2e-4, 2e-4, 1.5e-5);
  const std::string path = dir_ + "/two_sizes.h5";
  powderbed::bed::write_bed_h5(b, path);
  const auto r = run_app("bedstat", path + " --json --psd lognormal:d10=20e-6,d50=30e-6,d90=45e-6");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"diameter_quantiles\":{\"number\":{\"d10\":1e-05,\"d50\":1e-05,\"d90\":1e-05},"
                       "\"volume\":{\"d10\":1e-05,\"d50\":3e-05,\"d90\":3e-05}}"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\"psd_basis\":\"volume\""), std::string::npos) << r.out;  // the d-form default
  const auto table = run_app("bedstat", path + " --psd gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6");
  ASSERT_EQ(table.status, 0) << table.err;
  EXPECT_NE(table.out.find("D50 diameter, volume basis (m)"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("D50 diameter, number basis (m)"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("--psd basis"), std::string::npos) << table.out;
}
