// End-to-end tests of the deposit program: bad input exits 2 with one line; a small run writes
// a bed and a JSON summary.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

// Two 20 um particles resting 1 um above the floor of a 0.3 mm box.
std::string small_bed(const std::string& dir) {
  bed::Bed b;
  b.domain.upper = {0.3e-3, 0.3e-3, 0.3e-3};
  b.add(1e-4, 1.5e-4, 21e-6, 20e-6);
  b.add(2e-4, 1.5e-4, 21e-6, 20e-6);
  const std::string path = dir + "/in.h5";
  bed::write_bed_h5(b, path);
  return path;
}

}  // namespace

TEST(DepositCli, DtAboveStableBoundExits2WithOneLine) {
  const std::string dir = test::scratch_dir("deposit_dt");
  const auto r = test::run_app("deposit", "--in " + small_bed(dir) +
                                              " --t-end 1e-6 --dt 1e-6 --seed 1 --out " + dir +
                                              "/out.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--dt"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(dir + "/out.h5").good());  // no partial output
}

TEST(DepositCli, UnknownEffectAndNegativeDampingExit2) {
  const std::string dir = test::scratch_dir("deposit_scene");
  const std::string in = small_bed(dir);
  {
    std::ofstream scene(dir + "/bad.ini");
    scene << "[effects]\nmagnetism = true\n";
  }
  auto r = test::run_app("deposit", "--config " + dir + "/bad.ini --in " + in +
                                        " --t-end 1e-6 --seed 1 --out " + dir + "/out.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  r = test::run_app("deposit", "--in " + in + " --material.damping -0.1 --t-end 1e-6 --seed 1 "
                                              "--out " + dir + "/out.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("material.damping"), std::string::npos) << r.err;
}

TEST(DepositCli, SmallRunWritesBedAndJson) {
  const std::string dir = test::scratch_dir("deposit_run");
  const auto r = test::run_app("deposit", "--in " + small_bed(dir) +
                                              " --young-scale 1e3 --t-end 1e-4 --seed 1 --json "
                                              "--out " + dir + "/out.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"n\":2", "\"steps\"", "\"sim_time\"", "\"wall_time\"",
                          "\"particle_steps_per_s\"", "\"dt\"", "\"kinetic_energy\"",
                          "\"max_overlap\"", "\"lost\":0"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  }
  const bed::Bed out = bed::read_bed_h5(dir + "/out.h5");
  EXPECT_EQ(out.n(), 2u);
  EXPECT_TRUE(out.has_velocity());
  EXPECT_LT(out.z[0], 21e-6);  // it fell onto the floor
}

TEST(DepositCli, InsertionRegionTooSmallStatesAchievableCount) {
  // 40 um spheres in a 0.1 mm cube: at most a few dozen fit; 1000 are asked for.
  const std::string dir = test::scratch_dir("deposit_insert");
  const std::string common = "--psd mono:d=40e-6 --domain 1e-4,1e-4,1e-4 --young-scale 1e3 "
                             "--t-end 1e-6 --seed 4 --out " + dir + "/out.h5";
  auto r = test::run_app("deposit", "--count 1000 " + common);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--count"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(dir + "/out.h5").good());
  // The message names the achievable N ("N <= K"), and K is achievable: the same seed places it.
  const auto at = r.err.find("N <= ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const unsigned long achievable = std::stoul(r.err.substr(at + 5));
  EXPECT_GT(achievable, 0u);
  EXPECT_LT(achievable, 1000u);
  r = test::run_app("deposit", "--count " + std::to_string(achievable) + " " + common);
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST(DepositCli, ParticleOutsideTheDomainExits2) {
  const std::string dir = test::scratch_dir("deposit_outside");
  bed::Bed b;
  b.domain.upper = {0.3e-3, 0.3e-3, 0.3e-3};
  b.add(1e-4, 1.5e-4, 21e-6, 20e-6);
  b.add(2e-4, 1.5e-4, 0.4e-3, 20e-6);  // centre above the lid
  bed::write_bed_h5(b, dir + "/in.h5");
  auto r = test::run_app("deposit", "--in " + dir + "/in.h5 --young-scale 1e3 --t-end 1e-6 "
                                    "--seed 1 --out " + dir + "/out.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("outside the domain"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(dir + "/out.h5").good());
  // The same through --domain: a box smaller than the bed's.
  r = test::run_app("deposit", "--in " + small_bed(dir) + " --domain 0.15e-3,0.3e-3,0.3e-3 "
                               "--young-scale 1e3 --t-end 1e-6 --seed 1 --out " + dir + "/out.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_FALSE(std::ifstream(dir + "/out.h5").good());
}

TEST(DepositCli, KeBedSceneInsertsElevenHundredInTheTenDiameterBox) {
  // Issue 6: the [KE] beds, 1,100 spheres of 1 mm in a box 10 x 10 diameters (30 tall for the
  // 0-contact insertion); one step of 3.4e-6 s checks the insertion, not the settle.
  const std::string dir = test::scratch_dir("deposit_ke_bed");
  const std::string scene =
      std::string(POWDERBED_SOURCE_DIR) + "/data/scenes/ke2016-steel-1mm-held-lid-bed.ini";
  const auto r = test::run_app("deposit", "--config " + scene + " --t-end 1e-6 --lid.enabled "
                                          "false --crop-top false --seed 1 --json --out " +
                                              dir + "/out.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"n\":1100"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\"lid\""), std::string::npos) << r.out;  // the command line wins
  const bed::Bed out = bed::read_bed_h5(dir + "/out.h5");
  EXPECT_EQ(out.n(), 1100u);
  EXPECT_DOUBLE_EQ(out.domain.upper[0], 10e-3);
  EXPECT_DOUBLE_EQ(out.domain.upper[2], 30e-3);
}

TEST(DepositCli, KeBedSceneInsertsFromTheTopWithTheLinearLaw) {
  // The default [KE] bed scene: the linear law, insertion into a cube of 10 diameters. 2 ms of
  // the insertion at 5000 /s checks the set-up, not the fill (the validation study runs it).
  const std::string dir = test::scratch_dir("deposit_ke_insert");
  const std::string scene = std::string(POWDERBED_SOURCE_DIR) + "/data/scenes/ke2016-steel-1mm-bed.ini";
  const auto r = test::run_app("deposit", "--config " + scene + " --t-end 2e-3 --crop-top false "
                                          "--seed 1 --json --out " + dir + "/out.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"stopped_by\":\"time\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"contact_law\":\"linear\""), std::string::npos) << r.out;
  const bed::Bed out = bed::read_bed_h5(dir + "/out.h5");
  EXPECT_EQ(out.n(), 10u);  // one at t = 0 and one every 0.2 ms before 2 ms
  EXPECT_DOUBLE_EQ(out.domain.upper[2], 10e-3);
  EXPECT_EQ(out.provenance.contact.law, "linear");
  EXPECT_EQ(out.provenance.contact.stiffness, 1e5);
  EXPECT_EQ(out.provenance.contact.young, 198e9);
}

TEST(DepositCli, LidConsolidatesAndReportsItself) {
  // 60 spheres of 0.5 mm in a 2.5 mm box, softened 1e4 (dt ~1e-5 s): settle 0.1 s, then the lid
  // at 1 kPa; about 2e4 steps in all.
  const std::string dir = test::scratch_dir("deposit_lid");
  const std::string common = "--psd mono:d=0.5e-3 --count 60 --domain 2.5e-3,2.5e-3,6e-3 "
                             "--young-scale 1e4 --material.friction 0.3 --material.damping 0.5 "
                             "--t-end 0.1 --seed 3 --json ";
  const auto r = test::run_app("deposit", common + "--lid --lid.pressure 1e3 --lid.speed 5e-3 "
                                                   "--lid.hold 0.01 --lid.relax 0.05 "
                                                   "--crop-top true --out " + dir + "/lid.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"lid\":{", "\"start_z\"", "\"stop_z\"", "\"max_force\"",
                          "\"stopped_by\":\"force\"", "\"core_density\"", "\"lost\":0"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  }
  // --crop-top: the written box ends at the highest particle top.
  const bed::Bed out = bed::read_bed_h5(dir + "/lid.h5");
  double top = 0;
  for (std::size_t i = 0; i < out.n(); ++i) top = std::max(top, out.z[i] + out.radius[i]);
  EXPECT_DOUBLE_EQ(out.domain.upper[2], top);
}

TEST(DepositCli, BadLidExits2WithOneLine) {
  const std::string dir = test::scratch_dir("deposit_bad_lid");
  const std::string in = small_bed(dir);
  const std::string common = "--in " + in + " --young-scale 1e3 --t-end 1e-6 --seed 1 --out " +
                             dir + "/out.h5 --lid ";
  for (const std::string& bad : {std::string(""), std::string("--lid.pressure -1"),
                                 std::string("--lid.pressure 1e3 --lid.speed 0"),
                                 std::string("--lid.travel 1e-5 --effects.walls false")}) {
    const auto r = test::run_app("deposit", common + bad);
    EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("lid"), std::string::npos) << bad << ": " << r.err;
    EXPECT_FALSE(std::ifstream(dir + "/out.h5").good());
  }
}

TEST(DepositCli, LinearLawRunsAndTheBedRecordsHowItWasMade) {
  const std::string dir = test::scratch_dir("deposit_linear");
  const std::string in = small_bed(dir);
  const std::string common = "--in " + in + " --t-end 1e-5 --seed 1 --out " + dir + "/out.h5";
  auto r = test::run_app("deposit", common + " --contact.law linear --contact.stiffness 1e3 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"contact_law\":\"linear\""), std::string::npos) << r.out;
  bed::Bed out = bed::read_bed_h5(dir + "/out.h5");
  EXPECT_EQ(out.provenance.contact.law, "linear");
  EXPECT_EQ(out.provenance.contact.stiffness, 1e3);
  EXPECT_EQ(out.provenance.contact.young, 193e9);  // the default material, [GZ]'s 316L
  EXPECT_EQ(out.provenance.contact.poisson, 0.26);
  r = test::run_app("deposit", common + " --young-scale 1e3");
  ASSERT_EQ(r.status, 0) << r.err;
  out = bed::read_bed_h5(dir + "/out.h5");
  EXPECT_EQ(out.provenance.contact.law, "hertz");
  EXPECT_EQ(out.provenance.contact.young_scale, 1e3);
  EXPECT_EQ(out.provenance.contact.wall_young, 193e9);
}

TEST(DepositCli, BadContactLawExits2WithOneLine) {
  const std::string dir = test::scratch_dir("deposit_bad_law");
  const std::string common = "--in " + small_bed(dir) + " --t-end 1e-6 --seed 1 --out " + dir + "/out.h5 ";
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {"--contact.law jkr", {"contact.law", "jkr", "hertz, linear"}},
      {"--contact.law linear --contact.stiffness 0", {"contact.stiffness", "k_n > 0"}},
      {"--contact.law linear --contact.stiffness -1e5", {"contact.stiffness", "-100000"}},
      {"--contact.law linear", {"contact.stiffness", "missing"}},
      {"--contact.stiffness 1e5", {"contact.stiffness", "hertz"}},
      {"--contact.law linear --contact.stiffness 1e5 --young-scale 10", {"--young-scale", "linear"}}};
  for (const auto& [options, parts] : cases) {
    const auto r = test::run_app("deposit", common + options);
    EXPECT_EQ(r.status, 2) << options << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << r.err;
    for (const auto& part : parts) EXPECT_NE(r.err.find(part), std::string::npos) << part << " in " << r.err;
    EXPECT_FALSE(std::ifstream(dir + "/out.h5").good());
  }
}

TEST(DepositCli, InOnTheCommandLineWinsOverTheScenesPsd) {
  // A bed scene (psd, count, insertion) re-runs a given bed, as the consolidation of its beds
  // does; --in and --psd both on the command line stay refused.
  const std::string dir = test::scratch_dir("deposit_in_wins");
  const std::string in = small_bed(dir);
  const std::string scene = std::string(POWDERBED_SOURCE_DIR) + "/data/scenes/ke2016-steel-1mm-bed.ini";
  auto r = test::run_app("deposit", "--config " + scene + " --in " + in +
                                        " --t-end 1e-5 --seed 1 --json --out " + dir + "/out.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"n\":2,"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\"insertion\""), std::string::npos) << r.out;
  std::filesystem::remove(dir + "/out.h5");
  r = test::run_app("deposit", "--config " + scene + " --in " + in + " --psd mono:d=1e-3 "
                                   "--t-end 1e-5 --seed 1 --out " + dir + "/out.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--in and --psd"), std::string::npos) << r.err;
  r = test::run_app("deposit", "--config " + scene + " --in " + in + " --insert.enabled true "
                                   "--t-end 1e-5 --seed 1 --out " + dir + "/out.h5");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("insert.enabled"), std::string::npos) << r.err;
}

// A particle moving at 100 m/s in a box whose walls are switched off leaves it within the run:
// a run that loses particles is no result (issue 14: it wrote the bed and exited 0). Exit 3
// naming the count, no bed written; --allow-lost 1 accepts it and writes the one that stayed.
TEST(DepositCli, RunThatLosesParticlesExitsThree) {
  const std::string dir = test::scratch_dir("deposit_lost");
  bed::Bed b;
  b.domain.upper = {0.3e-3, 0.3e-3, 0.3e-3};
  b.add(1e-4, 1.5e-4, 21e-6, 20e-6);
  b.add(2e-4, 1.5e-4, 1.5e-4, 20e-6);
  b.vx = {0, 100};
  b.vy = {0, 0};
  b.vz = {0, 0};
  bed::write_bed_h5(b, dir + "/in.h5");
  // --thermo 0: the failure's one line alone on stderr, without the run's thermo table.
  const std::string base = "--in " + dir + "/in.h5 --t-end 2e-6 --effects.walls false "
                           "--effects.gravity false --thermo 0 --seed 1 --out " + dir + "/out.h5";
  const auto lost = test::run_app("deposit", base);
  EXPECT_EQ(lost.status, 3) << lost.err;
  EXPECT_EQ(lost.err_lines(), 1) << lost.err;
  EXPECT_NE(lost.err.find("1 of 2 particles left the box"), std::string::npos) << lost.err;
  EXPECT_FALSE(std::ifstream(dir + "/out.h5").good());
  const auto allowed = test::run_app("deposit", base + " --allow-lost 1 --json");
  EXPECT_EQ(allowed.status, 0) << allowed.err;
  EXPECT_EQ(test::json_number(allowed.out, "n"), 1.0) << allowed.out;
}
