// End-to-end tests of the keff program (issue 6): a column of touching spheres prints the JSON
// summary the issue asks for with the closed-form k_eff, writes the temperatures as a bed, and
// each bad input exits 2 with one line and writes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "cli_checks.hpp"
#include "run_command.hpp"

using namespace powderbed;

using powderbed::test::expect_refused;
using powderbed::test::json_number;

namespace {

const std::string kScene = std::string(POWDERBED_SOURCE_DIR) + "/data/scenes/ke2016-steel-1mm.ini";
// The column below stands on z; the scene's heat flows along x, between the side walls of a
// deposited bed, with radiation on: these tests take the room-temperature column's paths.
const std::string kConfig = "--config " + kScene + " --axis z --effects.radiation false";

// Four 1 mm steel spheres stacked on z, overlapping each other and the walls by 1e-3 r; recorded
// as made by a Hertz DEM at full stiffness (the scene asks for the Hertz correction).
bed::Bed column() {
  bed::Bed b;
  const double r = 0.5e-3, overlap = 1e-3 * r, pitch = 2 * r - overlap;
  for (int k = 0; k < 4; ++k) b.add(r, r, r - overlap + k * pitch, r);
  b.domain.upper = {2 * r, 2 * r, 3 * pitch + 2 * (r - overlap)};
  b.provenance.contact = {"hertz", 198e9, 0.28, 198e9, 0.28, 1.0, 0.0};
  return b;
}

std::string write_bed(const bed::Bed& b, const std::string& dir) {
  const std::string path = dir + "/bed.h5";
  bed::write_bed_h5(b, path);
  return path;
}


}  // namespace

TEST(KeffCli, ColumnPrintsJsonAndWritesTemperatures) {
  const std::string dir = test::scratch_dir("keff_run");
  const std::string bed_path = write_bed(column(), dir);
  // Geometric contact radius: the closed form below is that of the intersection circles.
  const auto r = test::run_app("keff", kConfig + " --bed " + bed_path +
                                           " --effects.gas false --contact.hertz-correction false"
                                           " --json --out " + dir + "/out.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << r.out;  // one JSON line
  for (const char* key : {"k_eff", "heat_flow_hot", "heat_flow_cold", "contact", "gas",
                          "radiation", "rattlers", "newton_iterations", "wall_time"})
    EXPECT_TRUE(std::isfinite(json_number(r.out, key))) << key << " in " << r.out;
  EXPECT_NE(r.out.find("\"share\":{"), std::string::npos) << r.out;
  EXPECT_EQ(json_number(r.out, "newton_iterations"), 1);
  EXPECT_EQ(json_number(r.out, "rattlers"), 0);
  EXPECT_EQ(json_number(r.out, "contact"), 1);
  // Closed form: five contacts 2 k_s a in series (two wall, three pair contacts); the JSON
  // prints shortest round-trip numbers, so the program's value comes through to round-off.
  const double r_p = 0.5e-3, overlap = 1e-3 * r_p, k_s = 28.555;  // the scene's k_s
  const double a_pair = std::sqrt(r_p * r_p - (r_p - overlap / 2) * (r_p - overlap / 2));
  const double a_wall = std::sqrt(r_p * r_p - (r_p - overlap) * (r_p - overlap));
  const double g = 1 / (2 / (2 * k_s * a_wall) + 3 / (2 * k_s * a_pair));
  const bed::Bed b = column();
  const double expected = g * b.domain.length(2) / (b.domain.length(0) * b.domain.length(1));
  EXPECT_NEAR(json_number(r.out, "k_eff"), expected, 1e-10 * expected);  // as the library test

  const bed::Bed out = bed::read_bed_any(dir + "/out.h5");
  ASSERT_EQ(out.temperature.size(), 4u);
  EXPECT_GT(out.temperature[3], out.temperature[0]);  // hot wall on top
  EXPECT_EQ(out.provenance.stage, "keff");

  // The profile beside it: one bin per diameter here (the column is four diameters tall less
  // the overlaps), one particle each, its mean the particle's temperature.
  std::ifstream profile(dir + "/out-profile.csv");
  ASSERT_TRUE(profile.good());
  std::string line;
  std::getline(profile, line);  // comment
  std::getline(profile, line);
  EXPECT_EQ(line, "z_m,mean_K,min_K,max_K,particles");
  for (std::size_t k = 0; k < 4; ++k) {
    ASSERT_TRUE(std::getline(profile, line));
    const std::size_t c1 = line.find(','), c2 = line.find(',', c1 + 1);
    EXPECT_NEAR(std::stod(line.substr(c1 + 1, c2 - c1 - 1)), out.temperature[k], 1e-6);  // %.9g
    EXPECT_EQ(line.substr(line.rfind(',') + 1), "1");
  }
  EXPECT_FALSE(std::getline(profile, line));
}

TEST(KeffCli, TemperatureOptionPutsTheWallsAroundIt) {
  const std::string dir = test::scratch_dir("keff_temperature");
  const std::string bed_path = write_bed(column(), dir);
  const std::string base = kConfig + " --bed " + bed_path + " --json ";
  const auto r = test::run_app("keff", base + "--temperature 1000");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_number(r.out, "t_hot"), 1000.5);
  EXPECT_EQ(json_number(r.out, "t_cold"), 999.5);
  // With the air polynomial k_g follows each link's temperature: at T ± 0.5 K the network is
  // the constant-k_g one at k_g(1000 K) to second order in β ΔT = k_g'/k_g · 0.5 K ≈ 4e-4
  // (measured 1.6e-8 relative, 1.6e-6 at ± 5 K); 1e-6 bounds it.
  const auto air = test::run_app("keff", base + "--temperature 1000 --gas.model air");
  ASSERT_EQ(air.status, 0) << air.err;
  char k_air[32];
  std::snprintf(k_air, sizeof k_air, "%.17g", json_number(air.out, "gas_conductivity"));
  const auto constant =
      test::run_app("keff", base + "--temperature 1000 --gas.conductivity " + k_air);
  ASSERT_EQ(constant.status, 0) << constant.err;
  EXPECT_NEAR(json_number(air.out, "k_eff"), json_number(constant.out, "k_eff"),
              1e-6 * json_number(constant.out, "k_eff"));
  EXPECT_GE(json_number(air.out, "newton_iterations"), 1);
}

TEST(KeffCli, RadiationTakesAShareThroughNewton) {
  const std::string dir = test::scratch_dir("keff_radiation");
  const std::string bed_path = write_bed(column(), dir);
  const auto r = test::run_app("keff", "--config " + kScene + " --axis z --bed " + bed_path +
                                           " --effects.radiation true --rays 500 --t-hot 1300"
                                           " --t-cold 1100 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GT(json_number(r.out, "radiation"), 0) << r.out;
  EXPECT_GE(json_number(r.out, "newton_iterations"), 1) << r.out;
  EXPECT_EQ(json_number(r.out, "rays"), 500) << r.out;
  EXPECT_EQ(json_number(r.out, "lost_rays"), 0) << r.out;
  const double hot = json_number(r.out, "heat_flow_hot");
  EXPECT_NEAR(json_number(r.out, "heat_flow_cold"), hot, 1e-8 * hot);  // the bound
  EXPECT_NEAR(json_number(r.out, "contact") + json_number(r.out, "gas") +
                  json_number(r.out, "radiation"),
              1, 1e-12);  // shares of one Tellegen sum
}

TEST(KeffCli, BadInputExitsTwoWithOneLine) {
  const std::string dir = test::scratch_dir("keff_bad");
  const std::string bed_path = write_bed(column(), dir);
  const std::string base = "--config " + kScene + " --out " + dir + "/out.h5 ";
  expect_refused(test::run_app("keff", base), dir, {"--bed"});
  expect_refused(test::run_app("keff", base + "--bed " + dir + "/missing.h5"), dir, {"missing.h5"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --axis w"), dir,
                 {"--axis", "w"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --t-hot 300 --t-cold 300"),
                 dir, {"t-hot"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --t-hot 290 --t-cold 300"),
                 dir, {"t-hot"});
  expect_refused(
      test::run_app("keff", base + "--bed " + bed_path + " --temperature 800 --t-hot 900"), dir,
      {"--temperature", "--t-hot"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --temperature -4"), dir,
                 {"--temperature"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path +
                                           " --gas.model air --t-hot 2500 --t-cold 300"),
                 dir, {"t-hot", "1900"});
  // A bed above its solidus is no longer powder: issue 36's --t-hot 1e5 gave k_eff = 40,580 W/mK.
  expect_refused(test::run_app("keff", base + "--bed " + bed_path +
                                           " --material 316L --gas.model constant --t-hot 1e5"),
                 dir, {"--t-hot", "100000 K", "solidus 1658 K"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --gas.model constant --t-hot 1e5"),
                 dir, {"--t-hot", "100000 K", "tungsten", "--trust-units"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path +
                                           " --material 316L --gas.model constant --temperature 1700"),
                 dir, {"--t-hot", "1700.5 K", "solidus"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --solid.conductivity -3"),
                 dir, {"solid.conductivity"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --gas.lens-region all"),
                 dir, {"gas.lens-region", "all"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --radiation.emissivity 0"),
                 dir, {"radiation.emissivity"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --radiation.model grey"),
                 dir, {"radiation.model", "grey", "radiosity"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --rays 0"), dir,
                 {"rays: 0"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --rays -5"), dir,
                 {"rays"});
  bed::Bed flat = column();  // the column as disks along y in a 2D bed: keff needs spheres
  flat.domain.dimension = 2;
  flat.y = flat.z;
  flat.z.assign(flat.n(), 0.0);
  flat.domain.upper[1] = flat.domain.upper[2];
  bed::write_bed_h5(flat, dir + "/flat.h5");
  expect_refused(test::run_app("keff", base + "--bed " + dir + "/flat.h5 --axis y"), dir,
                 {"axis", "2D"});
  // The column touches neither x face: along x there is no path to a wall, and the message
  // says how far the nearest particle is (tangent: 0 m).
  expect_refused(
      test::run_app("keff", "--config " + kScene + " --out " + dir + "/out.h5 --bed " + bed_path +
                                " --axis x --effects.gas false --effects.radiation false"),
      dir, {"hot wall", "nearest particle", "0 m"});
  expect_refused(test::run_app("keff", base + "--bed " + bed_path + " --contact.radius elastic"),
                 dir, {"contact.radius", "elastic", "geometric"});
}

TEST(KeffCli, HertzCorrectionReadsTheBedsContactLaw) {
  // The column recorded as made with the linear law k_n: the correction equates k_n delta_s with
  // (4/3) E* sqrt(R*) delta_h^{3/2}; contact only, so k_eff is the series sum in closed form.
  const std::string dir = test::scratch_dir("keff_linear");
  bed::Bed b = column();
  const double k_n = 1e5, e = 198e9, nu = 0.28;
  b.provenance.contact = {"linear", e, nu, e, nu, 1.0, k_n};
  const std::string bed_path = write_bed(b, dir);
  const std::string base =
      kConfig + " --bed " + bed_path + " --effects.gas false --contact.radius hertz --json";
  const auto r = test::run_app("keff", base);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"contact_law\":\"linear\""), std::string::npos) << r.out;
  const double r_p = 0.5e-3, overlap = 1e-3 * r_p, k_s = 28.555;  // the scene's k_s
  const double e_pair = 1 / (2 * (1 - nu * nu) / e);                // E* of equal materials
  const auto a_of = [&](double r_star, double delta) {
    const double delta_h = std::pow(3 * k_n * delta / (4 * e_pair * std::sqrt(r_star)), 2.0 / 3.0);
    return std::sqrt(r_star * delta_h);
  };
  const double g = 1 / (2 / (2 * k_s * a_of(r_p, overlap)) + 3 / (2 * k_s * a_of(r_p / 2, overlap)));
  const double expected = g * b.domain.length(2) / (b.domain.length(0) * b.domain.length(1));
  // A linear network solved by CG to 1e-10 of the flows (as the geometric test above).
  EXPECT_NEAR(json_number(r.out, "k_eff"), expected, 1e-8 * expected);
  // Reading it at twice the modulus shrinks every contact radius by 2^{-1/3}: k_eff too.
  const auto stiff = test::run_app("keff", base + " --contact.young 396e9");
  ASSERT_EQ(stiff.status, 0) << stiff.err;
  EXPECT_NEAR(json_number(stiff.out, "k_eff"), expected * std::pow(2.0, -1.0 / 3.0), 1e-8 * expected);
  // Options that agree with the record are accepted.
  EXPECT_EQ(test::run_app("keff", base + " --contact.law linear --contact.stiffness 1e5").status, 0);
}

TEST(KeffCli, ContactRecordMissingOrContradictedExitsTwo) {
  const std::string dir = test::scratch_dir("keff_bad_contact");
  const std::string base = kConfig + " --out " + dir + "/out.h5 --bed ";
  bed::Bed bare = column();
  bare.provenance.contact = {};  // e.g. a packgen bed or a LAMMPS dump
  bed::write_bed_h5(bare, dir + "/bare.h5");
  expect_refused(test::run_app("keff", base + dir + "/bare.h5"), dir,
                 {"contact.hertz-correction", "records no contact law"});
  // Without the correction the bare bed is fine (the geometric circle).
  EXPECT_EQ(test::run_app("keff", base + dir + "/bare.h5 --contact.hertz-correction false").status, 0);
  std::filesystem::remove(dir + "/out.h5");
  std::filesystem::remove(dir + "/out.xmf");
  std::filesystem::remove(dir + "/out-profile.csv");
  const std::string hertz = write_bed(column(), dir);  // hertz, young-scale 1
  expect_refused(test::run_app("keff", base + hertz + " --contact.young-scale 1000"), dir,
                 {"contact.young-scale", "1000", "contradicts"});
  expect_refused(test::run_app("keff", base + hertz + " --contact.law linear"), dir,
                 {"contact.law", "linear", "hertz"});
  expect_refused(test::run_app("keff", base + hertz + " --contact.stiffness 1e5"), dir,
                 {"contact.stiffness", "contradicts"});
  expect_refused(test::run_app("keff", base + hertz + " --contact.law jkr"), dir,
                 {"contact.law", "jkr", "hertz, linear"});
  expect_refused(test::run_app("keff", base + hertz + " --contact.stiffness -1"), dir,
                 {"contact.stiffness", "k_n > 0"});
  expect_refused(test::run_app("keff", base + hertz + " --contact.young 0"), dir,
                 {"contact.young", "E > 0"});
  // Stiffness-scaled fines (deposit fines.scaling = stiffness): their E is not the record's, so
  // the correction is refused; the record survives the file (written, then read by keff).
  bed::Bed scaled = column();
  scaled.provenance.contact.fines_stiffness_radius = 6e-6;
  bed::write_bed_h5(scaled, dir + "/scaled.h5");
  expect_refused(test::run_app("keff", base + dir + "/scaled.h5"), dir,
                 {"contact.hertz-correction", "6e-06", "fines.scaling = stiffness"});
  bed::Bed linear = column();
  linear.provenance.contact = {"linear", 198e9, 0.28, 198e9, 0.28, 1.0, 1e5};
  bed::write_bed_h5(linear, dir + "/linear.h5");
  expect_refused(test::run_app("keff", base + dir + "/linear.h5 --contact.stiffness 2e5"), dir,
                 {"contact.stiffness", "200000", "k_n = 100000 N/m"});
}

// A bed whose particles do not join the walls (one sphere on the floor, one under the lid, a
// diameter of gas between them, beyond the lenses' reach): k_eff is zero up to round-off, which
// is no result: exit 3 naming it, and no file written (issue 14: it used to print -7.9e-16).
TEST(KeffCli, BedThatDoesNotJoinTheWallsExitsThree) {
  const std::string dir = test::scratch_dir("keff_broken");
  bed::Bed b = column();
  const double r = 0.5e-3, overlap = 1e-3 * r;
  b.x = {r, r};
  b.y = {r, r};
  b.z = {r - overlap, 6 * r - r + overlap};  // a gap of 2 r: the lenses reach 0.2 r each
  b.radius = {r, r};
  b.id = {0, 1};
  b.domain.upper[2] = 6 * r;
  const std::string bed_path = write_bed(b, dir);
  const auto run = test::run_app("keff", kConfig + " --bed " + bed_path + " --out " +
                                            dir + "/out.h5");
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_NE(run.err.find("k_eff"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("no heat path"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/out-profile.csv"));
}
