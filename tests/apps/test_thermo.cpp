// deposit's thermo table (docs/deposit-thermo.md): a header once, aligned rows every
// --thermo N steps with the run's last step, the spread's layer and tool columns, --log holding
// the table and the summary, about 30 rows by default, nothing with --thermo 0, and the same bed
// with the table on or off.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string f; in >> f;) fields.push_back(f);
  return fields;
}

// The table's rows (after its header, which must come first and once); each row as wide as the
// header and with its number of columns.
std::vector<std::vector<std::string>> table_rows(const std::string& err, const std::string& header) {
  const auto lines = lines_of(err);
  EXPECT_FALSE(lines.empty());
  if (lines.empty()) return {};
  EXPECT_EQ(fields_of(lines[0]), fields_of(header)) << err;
  std::vector<std::vector<std::string>> rows;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    EXPECT_EQ(lines[k].size(), lines[0].size()) << "row " << k << " not aligned: " << lines[k];
    rows.push_back(fields_of(lines[k]));
    EXPECT_EQ(rows.back().size(), fields_of(header).size()) << lines[k];
  }
  return rows;
}

// Two 20 um particles side by side on the floor of a 0.3 mm box, each 0.1 um into the floor and
// 0.2 um into the other: at step 0 three contacts, the largest overlap 0.2 / 20 = 1e-2 r.
std::string pressed_pair(const std::string& dir) {
  bed::Bed b;
  b.domain.upper = {0.3e-3, 0.3e-3, 0.3e-3};
  b.add(1e-4, 1.5e-4, 19.9e-6, 20e-6);
  b.add(1e-4 + 39.8e-6, 1.5e-4, 19.9e-6, 20e-6);
  const std::string path = dir + "/in.h5";
  bed::write_bed_h5(b, path);
  return path;
}

const std::string kDropHeader = "Step Time KinEng MaxOverlap Contacts Lost";
const std::string kSpreadHeader = kDropHeader + " Layer ToolX";

// The spread of tests/apps/test_deposit_spread.cpp: 30 um spheres, a blade at 0.5 m/s.
std::string small_spread(const std::string& dir) {
  const std::string path = dir + "/spread.ini";
  std::ofstream f(path);
  f << "psd = mono:d=30e-6\ndomain = 1.5e-3,0.3e-3,0.6e-3\nperiodic = y\nyoung-scale = 1e4\n"
       "friction.model = history\n"
       "[recoater]\ntool = blade\nthickness = 100e-6\ngap = 60e-6\nspeed = 0.5\n"
       "start = 0.1e-3\nend = 1.2e-3\nlayer-thickness = 30e-6\n"
       "[supply]\nx0 = 0.16e-3\nx1 = 0.4e-3\nheight = 0.2e-3\ncount = 120\n"
       "[material]\nfriction = 0.5\nrolling = 0.05\n[effects]\ndrag = false\n";
  return path;
}

void expect_same_bed(const std::string& a_path, const std::string& b_path) {
  const bed::Bed a = bed::read_bed_h5(a_path), b = bed::read_bed_h5(b_path);
  ASSERT_EQ(a.n(), b.n());
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.vx, b.vx);
  EXPECT_EQ(a.vz, b.vz);
}

}  // namespace

TEST(Thermo, DropPrintsAlignedRowsEveryNStepsAndTheLogHoldsTableAndSummary) {
  const std::string dir = test::scratch_dir("thermo_drop");
  const std::string base = "--in " + pressed_pair(dir) + " --young-scale 1e3 --t-end 1e-4 --seed 1 --json ";
  const auto r = test::run_app("deposit", base + "--thermo 100 --log " + dir + "/run.log --out " +
                                              dir + "/a.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = table_rows(r.err, kDropHeader);
  const auto steps = static_cast<std::uint64_t>(test::json_number(r.out, "steps"));
  ASSERT_GE(rows.size(), 3u);
  // Step 0, every 100th step, and the last.
  for (std::size_t k = 0; k + 1 < rows.size(); ++k) EXPECT_EQ(std::stoull(rows[k][0]), 100 * k);
  EXPECT_EQ(std::stoull(rows.back()[0]), steps);
  EXPECT_EQ(rows.size(), (steps + 99) / 100 + 1);
  EXPECT_EQ(rows[0][1], "0.000000e+00");
  EXPECT_EQ(rows[0][2], "0.000000e+00");  // at rest
  EXPECT_NEAR(std::stod(rows[0][3]), 1e-2, 1e-6);
  EXPECT_EQ(rows[0][4], "3");
  EXPECT_EQ(rows[0][5], "0");
  // The last row is the end the JSON reports.
  const double ke = test::json_number(r.out, "kinetic_energy");
  EXPECT_NEAR(std::stod(rows.back()[2]), ke, 1e-6 * ke);
  EXPECT_NEAR(std::stod(rows.back()[1]), test::json_number(r.out, "sim_time"), 1e-9);
  EXPECT_NEAR(std::stod(rows.back()[3]), test::json_number(r.out, "max_overlap"),
              1e-4 * test::json_number(r.out, "max_overlap"));
  EXPECT_EQ(test::read_text(dir + "/run.log"), r.err + r.out);
  // The table reads the state only: the bed is the same without it, and --thermo 0 prints none.
  const auto off = test::run_app("deposit", base + "--thermo 0 --out " + dir + "/b.h5");
  ASSERT_EQ(off.status, 0) << off.err;
  EXPECT_EQ(off.err, "");
  expect_same_bed(dir + "/a.h5", dir + "/b.h5");
}

TEST(Thermo, DefaultIsAboutThirtyRowsAndTheSpreadAddsLayerAndTool) {
  const std::string dir = test::scratch_dir("thermo_spread");
  const std::string base = "--config " + small_spread(dir) + " --seed 3 --layers 2 ";
  const auto r = test::run_app("deposit", base + "--out " + dir + "/a.h5 --log " + dir + "/run.log");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = table_rows(r.err, kSpreadHeader);
  EXPECT_GE(rows.size(), 20u);
  EXPECT_LE(rows.size(), 50u);
  // Layer 1 then layer 2, each ending with the tool at recoater.end; the tool between its ends.
  std::uint64_t layer = 1, previous_step = 0;
  for (const auto& row : rows) {
    const std::uint64_t l = std::stoull(row[6]);
    EXPECT_TRUE(l == layer || l == layer + 1) << row[6];
    layer = l;
    EXPECT_GT(std::stoull(row[0]), previous_step);
    previous_step = std::stoull(row[0]);
    EXPECT_GE(std::stod(row[7]), 0.1e-3 - 1e-12);
    EXPECT_LE(std::stod(row[7]), 1.2e-3 + 1e-12);
  }
  EXPECT_EQ(layer, 2u);
  EXPECT_NEAR(std::stod(rows.back()[7]), 1.2e-3, 1e-9);
  const std::string log = test::read_text(dir + "/run.log");
  EXPECT_EQ(log, r.err + r.out);
  const auto off = test::run_app("deposit", base + "--thermo 0 --out " + dir + "/b.h5");
  ASSERT_EQ(off.status, 0) << off.err;
  EXPECT_EQ(off.err, "");
  expect_same_bed(dir + "/a.h5", dir + "/b.h5");
}

TEST(Thermo, LogClashingWithTheInputExits2) {
  const std::string dir = test::scratch_dir("thermo_log");
  const std::string in = pressed_pair(dir);
  const auto r = test::run_app("deposit", "--in " + in + " --t-end 1e-6 --seed 1 --log " + in +
                                              " --out " + dir + "/a.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--log"), std::string::npos) << r.err;
}

// With insertion the bed is a pool parked at the box's centre until each particle enters: the
// rows count only the particles in the box (the pool's parked spheres lie inside each other).
TEST(Thermo, InsertionRowsCountOnlyTheParticlesThatEntered) {
  const std::string dir = test::scratch_dir("thermo_insert");
  const auto r = test::run_app("deposit", "--psd mono:d=0.5e-3 --count 20 --domain 2.5e-3,2.5e-3,6e-3 "
                                          "--young-scale 1e4 --insert.enabled true --insert.rate 2000 "
                                          "--insert.speed 0.1 --t-end 0.02 --seed 3 --thermo 100 "
                                          "--out " + dir + "/a.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = table_rows(r.err, kDropHeader);
  ASSERT_GT(rows.size(), 10u);
  for (const auto& row : rows) EXPECT_LT(std::stod(row[3]), 0.1) << row[0];
  EXPECT_EQ(rows[0][4], "0");  // the first particle alone, in the air
}
