// --material, --list-materials and --print-config end to end (docs/physics.md "Materials"): one
// material file fills deposit's, sinter's and keff's options alike, an option given next to it
// wins, and every program's --print-config reads back with --config to the same options.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_checks.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/material_file.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

const std::vector<std::string> kMaterials = {"316L",  "AlSi10Mg",  "IN625",
                                             "IN718", "Ti-6Al-4V", "copper"};

// The value printed for `key` by --print-config ("key = value" lines, or the commented-out
// "# key = value  (from --material)" of a value the material file filled, or a default's);
// "" when absent.
std::string config_value(const std::string& text, const std::string& key) {
  for (const std::string& prefix : {"\n" + key + " = ", "\n# " + key + " = "}) {
    const auto at = ("\n" + text).find(prefix);
    if (at == std::string::npos) continue;
    const auto start = at + prefix.size() - 1;
    const std::string line = text.substr(start, text.find('\n', start) - start);
    return line.substr(0, line.find("  ("));
  }
  return "";
}

double config_number(const std::string& text, const std::string& key) {
  const std::string v = config_value(text, key);
  return v.empty() ? NAN : std::stod(v);
}

// Twelve 15 um particles resting on the floor of a 0.2 x 0.1 mm bed (sinter's small test bed).
std::string small_bed(const std::string& dir) {
  bed::Bed b;
  b.domain.upper = {0.2e-3, 0.1e-3, 0.1e-3};
  const double r = 15e-6;
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 6; ++i)
      b.add(25e-6 + i * 29.9e-6, 35e-6 + row * 29.9e-6, r * (1 - 1e-4), r);
  const std::string path = dir + "/bed.h5";
  bed::write_bed_h5(b, path);
  return path;
}

}  // namespace

TEST(MaterialCli, ListMaterialsNamesTheSixWithDescriptions) {
  for (const char* app : {"deposit", "sinter", "keff"}) {
    const auto r = test::run_app(app, "--list-materials");
    ASSERT_EQ(r.status, 0) << app << r.err;
    for (const auto& name : kMaterials)
      EXPECT_NE(r.out.find(name + "  "), std::string::npos) << app << name;
    int lines = 0;
    for (char c : r.out) lines += c == '\n';
    EXPECT_EQ(lines, 6) << r.out;
    const auto j = test::run_app(app, "--list-materials --json");
    ASSERT_EQ(j.status, 0) << j.err;
    EXPECT_EQ(j.out.rfind("{\"materials\":[{\"name\":", 0), 0u) << j.out;
    EXPECT_NE(j.out.find("\"description\":\"pure copper"), std::string::npos) << j.out;
  }
}

TEST(MaterialCli, DepositTakesTheElasticConstantsAndDensity) {
  // The word that was "ambiguous" (Boost's prefix match of material.*) is the option now.
  auto r = test::run_app("deposit", "--material 316L --print-config");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(config_number(r.out, "material.density"), 7952);
  EXPECT_EQ(config_number(r.out, "material.young"), 193e9);
  r = test::run_app("deposit", "--material Ti-6Al-4V --material.density 4000 --print-config");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(config_number(r.out, "material.density"), 4000);  // given: it wins
  EXPECT_EQ(config_number(r.out, "material.young"), 114e9);
  EXPECT_EQ(config_number(r.out, "material.poisson"), 0.34);
  // A scene file's value wins over a material the scene file names, and gives way to one typed
  // at the command line (a 316L scene run as copper takes copper's numbers).
  const std::string dir = test::scratch_dir("material_scene");
  std::ofstream(dir + "/own.ini") << "material = Ti-6Al-4V\n[material]\npoisson = 0.3\n";
  r = test::run_app("deposit", "--config " + dir + "/own.ini --print-config");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(config_number(r.out, "material.poisson"), 0.3);
  EXPECT_EQ(config_number(r.out, "material.young"), 114e9);
  std::ofstream(dir + "/steel.ini") << "[material]\npoisson = 0.26\nyoung = 193e9\n";
  r = test::run_app("deposit", "--config " + dir + "/steel.ini --material copper --print-config");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(config_number(r.out, "material.poisson"), 0.34);
  EXPECT_EQ(config_number(r.out, "material.young"), 119e9);
  // A relative material path in a scene file is found beside the scene, as sinter's table is.
  std::filesystem::copy_file(bed::materials_folder() + "/copper.csv", dir + "/mine.csv");
  std::ofstream(dir + "/mine.ini") << "material = mine.csv\n";
  r = test::run_app("deposit", "--config " + dir + "/mine.ini --print-config");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(config_number(r.out, "material.young"), 119e9);
}

TEST(MaterialCli, DepositRunRecordsTheMaterialsModulus) {
  const std::string dir = test::scratch_dir("material_deposit");
  bed::Bed b;
  b.domain.upper = {0.3e-3, 0.3e-3, 0.3e-3};
  b.add(1e-4, 1.5e-4, 21e-6, 20e-6);
  bed::write_bed_h5(b, dir + "/in.h5");
  const auto r = test::run_app("deposit", "--in " + dir +
                                              "/in.h5 --material copper --t-end 1e-6 "
                                              "--seed 1 --out " +
                                              dir + "/out.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  const bed::Bed out = bed::read_bed_h5(dir + "/out.h5");
  EXPECT_EQ(out.provenance.contact.young, 119e9);
  EXPECT_EQ(out.provenance.contact.poisson, 0.34);
  EXPECT_NE(out.provenance.scene.find("material = copper"), std::string::npos);
}

TEST(MaterialCli, SinterTakesTheTableAndPhaseChange) {
  const auto r = test::run_app("sinter", "--material copper --print-config");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(config_value(r.out, "material.table"), bed::materials_folder() + "/copper.csv");
  EXPECT_EQ(config_number(r.out, "material.melting-point"), 1357.77);
  EXPECT_EQ(config_number(r.out, "material.boiling-point"), 2835);
  EXPECT_EQ(config_number(r.out, "material.latent-melt"), 2.087e5);
  EXPECT_EQ(config_number(r.out, "material.hold-from"), 1200);
  EXPECT_EQ(config_number(r.out, "laser.absorptivity"), 0.03);
  const auto given =
      test::run_app("sinter", "--material copper --laser.absorptivity 0.5 --print-config");
  EXPECT_EQ(config_number(given.out, "laser.absorptivity"), 0.5);
  // The paper's 316L scene run as copper: the scene's table gives way to the typed material.
  const auto scene = test::run_app(
      "sinter", "--config " + std::string(POWDERBED_SOURCE_DIR) +
                    "/data/scenes/gz2016-sinter.ini --material copper --print-config");
  ASSERT_EQ(scene.status, 0) << scene.err;
  EXPECT_EQ(config_value(scene.out, "material.table"), bed::materials_folder() + "/copper.csv");
  EXPECT_EQ(config_number(scene.out, "material.melting-point"), 1357.77);
}

TEST(MaterialCli, EveryShippedMaterialPassesSintersChecks) {
  // Each file's table, melting and hold temperatures are consistent with sinter's model (the
  // phase-change window of 20 K fits between the table and T_m, T_v above it): --explain
  // builds the whole solver and exits 0.
  const std::string dir = test::scratch_dir("material_sinter");
  const std::string bed_path = small_bed(dir);
  for (const auto& name : kMaterials) {
    const auto r = test::run_app("sinter", "--bed " + bed_path + " --material " + name +
                                               " --substrate.nodes 21,11,11 --substrate.depth "
                                               "0.1e-3 --explain --json");
    EXPECT_EQ(r.status, 0) << name << ": " << r.err;
    EXPECT_EQ(r.out.rfind("{\"laser_flux\":", 0), 0u) << name << ": " << r.out;
  }
}

TEST(MaterialCli, KeffTakesTheTablesConductivityAtTheBedTemperature) {
  // Copper's table: 401 W/mK at 293 K, 393 at 400 K; the walls' mean 300 K interpolates to
  // 401 - 8 x 7 / 107.
  auto r = test::run_app("keff", "--material copper --print-config");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NEAR(config_number(r.out, "solid.conductivity"), 401 - 8.0 * 7 / 107, 1e-9);
  r = test::run_app("keff", "--material 316L --temperature 700 --print-config");
  EXPECT_NEAR(config_number(r.out, "solid.conductivity"), 19.0, 1e-12);  // a table row
  r = test::run_app("keff", "--material 316L --solid.conductivity 16.2 --print-config");
  EXPECT_EQ(config_number(r.out, "solid.conductivity"), 16.2);
}

TEST(MaterialCli, UnknownMaterialOrBadFileExits2WithOneLine) {
  const std::string dir = test::scratch_dir("material_bad");
  test::expect_refused(test::run_app("deposit", "--material unobtainium --print-config"), dir,
                       {"--material: 'unobtainium'", "316L", "--list-materials"});
  std::ofstream(dir + "/bad.csv") << "density,7.9,g/cm^3,typed by hand\n";
  test::expect_refused(test::run_app("sinter", "--material " + dir + "/bad.csv --print-config"),
                       dir, {"--material", "bad.csv:1", "kg/m^3"});
}

TEST(PrintConfig, EveryProgramReadsItsOwnConfigBack) {
  const std::string dir = test::scratch_dir("print_config");
  const std::vector<std::pair<std::string, std::string>> runs = {
      {"packgen",
       "--dim 3 --psd mono:d=30e-6 --count 10 --domain 1e-3,1e-3,1e-3 --seed 1 --out p.h5"},
      {"deposit",
       "--material IN718 --psd lognormal:d10=20e-6,d50=30e-6,d90=45e-6 --count 5 "
       "--domain 1e-3,1e-3,1e-3 --seed 2 --until-rest"},
      {"sinter", "--material Ti-6Al-4V --power 150 --effects.wetting false"},
      {"keff", "--material AlSi10Mg --temperature 500"},
      {"bedstat", "a.h5 b.h5 --voronoi --tol 1e-3"},
      {"bedconv", "in.h5 out.data"}};
  for (const auto& [app, args] : runs) {
    const auto first = test::run_app(app, args + " --print-config");
    ASSERT_EQ(first.status, 0) << app << ": " << first.err;
    EXPECT_TRUE(first.err.empty()) << app << ": " << first.err;
    const std::string scene = dir + "/" + app + ".ini";
    std::ofstream(scene) << first.out;
    const auto again = test::run_app(app, "--config " + scene + " --print-config");
    ASSERT_EQ(again.status, 0) << app << ": " << again.err;
    EXPECT_EQ(again.out, first.out) << app;
  }
}

TEST(MaterialCli, TheSameTrackMeltsTitaniumButNotCopper) {
  // [GZ]'s laser (200 W, 2 m/s, w = 54 um) over twelve 30 um particles; only --material
  // differs. Per particle the beam delivers I0 pi r^2 = 31 W for about w / v = 27-54 us. Copper
  // (alpha 0.03) absorbs about 0.9 W of it directly, ~3e-5 J; its rough plate reflects 97 % of
  // what reaches it and scatters it sideways into the particles, which brings each to ~7e-5 J
  // (traced: 0.88 mJ over the twelve; with a mirror plate 0.60 mJ), short of the 8e-5 J that
  // heats its 1.3e-10 kg from 363 K and melts it wholly (c dT + L_m = 6.3e5 J/kg); its
  // 400 W/mK substrate drains the rest. So copper's particles may reach the melting window but
  // none passes through it. Ti-6Al-4V (alpha 0.4) absorbs 12 W, about 5e-4 J, six times the
  // 8e-5 J its 6.3e-11 kg need (1.3e6 J/kg): every particle melts. So the numbers of the files
  // reach the solver.
  const std::string dir = test::scratch_dir("material_track");
  const std::string bed_path = small_bed(dir);
  const auto run = [&](const std::string& material) {
    return test::run_app("sinter", "--bed " + bed_path + " --material " + material +
                                       " --substrate.nodes 21,11,11 --substrate.depth 0.1e-3 "
                                       "--snapshots 0 --json --out " + dir + "/out.h5");
  };
  const auto copper = run("copper");
  ASSERT_EQ(copper.status, 0) << copper.err;
  // Top of copper's melting window: T_m of data/materials/copper.csv + the default ΔT / 2.
  const double copper_liquid = 1357.77 + 0.5 * 20;
  EXPECT_LT(test::json_number(copper.out, "max_temperature_particles"), copper_liquid)
      << copper.out;
  const auto titanium = run("Ti-6Al-4V");
  ASSERT_EQ(titanium.status, 0) << titanium.err;
  EXPECT_EQ(test::json_number(titanium.out, "particles_molten"), 12) << titanium.out;
  // The absorbed share follows the flat absorptivity of each file (0.03 against 0.4).
  EXPECT_LT(test::json_number(copper.out, "absorptance"),
            0.2 * test::json_number(titanium.out, "absorptance"));
}

// Issue 31's bad input: a material file that lacks what a model asks for (n, k for Fresnel; the
// boiling point and molar mass for evaporation; the surface tension for the depression), or a
// negative k, exits 2 with one line naming the missing key and the way out.
TEST(MaterialCli, ProcessModelsRefuseAMaterialWithoutTheirKeys) {
  const std::string dir = test::scratch_dir("material_process");
  const std::string bed_path = small_bed(dir);
  // 316L's file without its optics, evaporation and depression keys.
  std::ifstream in(std::string(POWDERBED_SOURCE_DIR) + "/data/materials/316L.csv");
  std::ofstream out(dir + "/bare.csv");
  for (std::string line; std::getline(in, line);) {
    const bool dropped = line.rfind("index_", 0) == 0 || line.rfind("molar_mass", 0) == 0 ||
                         line.rfind("surface_tension", 0) == 0 || line.rfind("boiling_point", 0) == 0;
    if (!dropped) out << line << '\n';
  }
  out.close();
  const std::string run = "--bed " + bed_path + " --substrate.nodes 21,11,11 --substrate.depth "
                          "0.1e-3 --explain --material " + dir + "/bare.csv";
  test::expect_refused(test::run_app("sinter", run), dir,
                       {"--material", "laser.index-n-solid", "laser.optics = fresnel",
                        "laser.optics = constant"});
  test::expect_refused(test::run_app("sinter", run + " --laser.optics constant"), dir,
                       {"--material", "material.boiling-point", "effects.evaporation"});
  test::expect_refused(
      test::run_app("sinter", run + " --laser.optics constant --effects.evaporation false "
                                    "--material.boiling-point 3100 --material.molar-mass 0.056"),
      dir, {"--material", "material.surface-tension", "effects.depression"});
  EXPECT_EQ(test::run_app("sinter", run + " --laser.optics constant --effects.evaporation false "
                                          "--effects.depression false").status,
            0);
  test::expect_refused(test::run_app("sinter", "--bed " + bed_path +
                                                   " --explain --laser.index-k-solid -1"),
                       dir, {"laser.index-k-solid", "accepted", "k > 0"});
}
