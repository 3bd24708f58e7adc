// Every program's --json summary carries "units" (issue 34, powderbed/bed/json_units.hpp): each number of
// the summary (a number, null for a non-finite one, or an array of numbers) has its key in the
// "units" object, with its SI unit. One test per program, with options that bring out the
// summary's optional parts (the lid, insertion, fusion, ray tracing, bedstat's statistics).
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

struct Keys {
  std::set<std::string> numeric;  // keys of numbers outside "units"
  std::set<std::string> units;    // the keys "units" names
};

bool number_starts(char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == 'n'; }

// The keys of a JSON text (the programs' one-line summaries: no strings hold a bare quote).
Keys scan(const std::string& json) {
  Keys keys;
  int depth = 0, units_depth = -1;
  const auto skip = [&](std::size_t at) {
    while (at < json.size() && std::isspace(static_cast<unsigned char>(json[at]))) ++at;
    return at;
  };
  for (std::size_t i = 0; i < json.size();) {
    const char c = json[i];
    if (c == '"') {
      std::size_t j = i + 1;
      std::string text;
      while (j < json.size() && json[j] != '"') {
        if (json[j] == '\\') text += json[j++];
        text += json[j++];
      }
      const std::size_t after = skip(j + 1);
      if (after >= json.size() || json[after] != ':') {  // a string value
        i = after;
        continue;
      }
      const std::size_t value = skip(after + 1);
      const char first = json[value];
      if (units_depth >= 0 && depth > units_depth) {
        keys.units.insert(text);
      } else if (number_starts(first) || (first == '[' && number_starts(json[skip(value + 1)]))) {
        keys.numeric.insert(text);
      }
      if (text == "units" && first == '{') units_depth = depth;
      i = value;
      continue;
    }
    if (c == '{' || c == '[') ++depth;
    if (c == '}' || c == ']') {
      --depth;
      if (depth == units_depth) units_depth = -1;
    }
    ++i;
  }
  return keys;
}

// Every number of `json` has a unit; the listed keys have the listed units.
void expect_units(const test::CommandResult& r,
                  std::initializer_list<std::pair<const char*, const char*>> spot_checks) {
  ASSERT_EQ(r.status, 0) << r.err;
  const Keys keys = scan(r.out);
  EXPECT_FALSE(keys.numeric.empty()) << r.out;
  for (const std::string& key : keys.numeric)
    EXPECT_TRUE(keys.units.count(key)) << "no unit for \"" << key << "\" in " << r.out;
  for (const std::string& key : keys.units)
    EXPECT_TRUE(keys.numeric.count(key)) << "a unit for \"" << key << "\", not in the summary";
  const auto units = r.out.substr(r.out.find("\"units\":{"));
  for (const auto& [key, unit] : spot_checks) {
    std::string entry;  // "key":"unit"
    entry.append(1, '"').append(key).append("\":\"").append(unit).append(1, '"');
    EXPECT_NE(units.find(entry), std::string::npos) << key << " in " << units;
  }
}

const std::string kSource = POWDERBED_SOURCE_DIR;

// A 1-layer blade spread of 30 um spheres (tests/apps/test_deposit_spread.cpp's scene).
std::string spread_scene(const std::string& dir) {
  const std::string path = dir + "/spread.ini";
  std::ofstream f(path);
  f << "psd = mono:d=30e-6\ndomain = 1.5e-3,0.3e-3,0.6e-3\nperiodic = y\nyoung-scale = 1e4\n"
       "[recoater]\ntool = blade\nthickness = 100e-6\ngap = 60e-6\nspeed = 0.5\n"
       "start = 0.1e-3\nend = 1.2e-3\n"
       "[supply]\nx0 = 0.16e-3\nx1 = 0.4e-3\nheight = 0.2e-3\ncount = 120\n[effects]\ndrag = false\n";
  return path;
}

// Two rows of six 15 um particles resting on the floor, neighbours slightly overlapping.
std::string sinter_bed(const std::string& dir) {
  bed::Bed b;
  b.domain.upper = {0.2e-3, 0.1e-3, 0.1e-3};
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 6; ++i) b.add(25e-6 + i * 29.9e-6, 35e-6 + row * 29.9e-6, 15e-6 * (1 - 1e-4), 15e-6);
  bed::write_bed_h5(b, dir + "/bed.h5");
  return dir + "/bed.h5";
}

}  // namespace

TEST(JsonUnits, ScanFindsNumbersArraysAndNullsOutsideUnits) {
  const Keys k = scan("{\"a\":1,\"b\":\"s\",\"c\":[1,2],\"d\":null,\"e\":{\"f\":-2e-3,\"g\":true},"
                      "\"h\":[{\"i\":3}],\"units\":{\"a\":\"m\",\"z\":\"1\"}}");
  EXPECT_EQ(k.numeric, (std::set<std::string>{"a", "c", "d", "f", "i"}));
  EXPECT_EQ(k.units, (std::set<std::string>{"a", "z"}));
}

TEST(JsonUnits, Packgen) {
  const std::string dir = test::scratch_dir("units_packgen");
  expect_units(test::run_app("packgen", "--dim 2 --domain 4e-6,4e-6 --psd mono:r=0.2e-6 --seed 3 "
                                        "--approach 1 --json --out " + dir + "/bed.h5"),
               {{"density", "1"}, {"wall_time", "s"}});
}

TEST(JsonUnits, DepositDropWithLidAndInsertion) {
  const std::string dir = test::scratch_dir("units_deposit");
  expect_units(test::run_app("deposit", "--psd mono:d=0.5e-3 --count 60 --domain 2.5e-3,2.5e-3,6e-3 "
                                        "--young-scale 1e4 --material.damping 0.5 --t-end 0.05 "
                                        "--seed 3 --json --thermo 0 --lid --lid.pressure 1e3 "
                                        "--lid.speed 5e-3 --lid.hold 0.005 --lid.relax 0.02 --out " +
                                        dir + "/lid.h5"),
               {{"dt", "s"}, {"kinetic_energy", "J"}, {"max_force", "N"}, {"stiffness", "N/m"}});
  expect_units(test::run_app("deposit", "--psd mono:d=0.5e-3 --count 20 --domain 2.5e-3,2.5e-3,6e-3 "
                                        "--young-scale 1e4 --insert.enabled true --insert.rate 2000 "
                                        "--insert.speed 0.1 --t-end 0.02 --seed 3 --json --thermo 0 "
                                        "--out " + dir + "/ins.h5"),
               {{"inserted", "1"}, {"end_time", "s"}});
}

TEST(JsonUnits, DepositSpread) {
  const std::string dir = test::scratch_dir("units_spread");
  expect_units(test::run_app("deposit", "--config " + spread_scene(dir) + " --seed 3 --json "
                                        "--thermo 0 --out " + dir + "/s.h5"),
               {{"tool_bottom", "m"}, {"max_tool_force", "N"}, {"sim_time", "s"}});
}

TEST(JsonUnits, SinterRunWithFusionAndExplain) {
  const std::string dir = test::scratch_dir("units_sinter");
  const std::string base = "--config " + kSource + "/data/scenes/gz2016-sinter.ini --bed " +
                           sinter_bed(dir) + " --substrate.nodes 21,11,11 --substrate.depth 0.1e-3 ";
  expect_units(test::run_app("sinter", base + "--out " + dir + "/out.h5 --fuse --json"),
               {{"max_temperature", "K"}, {"evaporated_mass", "kg"}, {"width", "m"},
                {"laser_particles", "J"}, {"extinction", "1/m"}, {"threshold", "K"}});
  expect_units(test::run_app("sinter", base + "--explain --json"),
               {{"laser_flux", "W/m^2"}, {"dwell_time", "s"}, {"cooling_time", "s"}});
}

TEST(JsonUnits, Keff) {
  const std::string dir = test::scratch_dir("units_keff");
  bed::Bed b;  // four 1 mm spheres stacked on z, touching each other and the walls
  const double r = 0.5e-3, overlap = 1e-3 * r, pitch = 2 * r - overlap;
  for (int k = 0; k < 4; ++k) b.add(r, r, r - overlap + k * pitch, r);
  b.domain.upper = {2 * r, 2 * r, 3 * pitch + 2 * (r - overlap)};
  bed::write_bed_h5(b, dir + "/bed.h5");
  expect_units(test::run_app("keff", "--config " + kSource + "/data/scenes/ke2016-steel-1mm.ini "
                                     "--axis z --contact.hertz-correction false --bed " + dir +
                                     "/bed.h5 --json"),
               {{"k_eff", "W/(m K)"}, {"t_hot", "K"}, {"heat_flow_hot", "W"}});
}

TEST(JsonUnits, BedstatWithEveryStatisticAndASpreadLayer) {
  const std::string dir = test::scratch_dir("units_bedstat");
  const auto spread = test::run_app("deposit", "--config " + spread_scene(dir) +
                                                   " --seed 3 --thermo 0 --out " + dir + "/s.h5");
  ASSERT_EQ(spread.status, 0) << spread.err;
  expect_units(test::run_app("bedstat", dir + "/s.h5 --json --layer 0,60e-6 --profile 4 --rdf 4 "
                                        "--voronoi --order --histogram 4 --psd mono:d=30e-6 "
                                        "--spread --feed " + dir + "/s.h5"),
               {{"box_density", "1"}, {"d50", "m"}, {"sa", "m"}, {"1e-06", "1"}});
}

TEST(JsonUnits, Bedconv) {
  const std::string dir = test::scratch_dir("units_bedconv");
  bed::Bed b;
  b.domain.upper = {1e-4, 1e-4, 1e-4};
  b.add(5e-5, 5e-5, 2e-5, 2e-5);
  bed::write_bed_h5(b, dir + "/in.h5");
  expect_units(test::run_app("bedconv", dir + "/in.h5 " + dir + "/out.csv --json"),
               {{"particles", "1"}});
}

TEST(JsonUnits, Build) {
  const std::string dir = test::scratch_dir("units_build");
  expect_units(test::run_app("build", "--config " POWDERBED_TEST_DATA "/build-small/build.ini "
                                      "--layers 1 --json --out " + dir + "/run"),
               {{"scanned_area", "m^2"}, {"solid_mass", "kg"}, {"mean_track_depth", "m"}});
}
