// Material files (bed/material_file.hpp, docs/physics.md "Materials"): the six shipped powders
// load with every property and its source; bad files are refused naming the file and the line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/material_file.hpp"

using namespace powderbed;

namespace {

class TempFile {
 public:
  TempFile(const std::string& name, const std::string& text)
      : path_("/tmp/powderbed_material_" + std::to_string(::getpid()) + "_" + name + ".csv") {
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

const char* kTable =
    "temperature_K,specific_heat_J_per_kgK,conductivity_W_per_mK,density_kg_per_m3,phase\n"
    "293,452,13.3,7952,solid\n366,485,14.3,7919,solid\n1700,815,32.4,7300,liquid\n";

void expect_refused(const std::string& name, const std::string& scalars, const std::string& what) {
  const TempFile file(name, scalars + kTable);
  try {
    bed::read_material_file(file.path());
    ADD_FAILURE() << name << ": accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file.path()), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  }
}

}  // namespace

TEST(MaterialFile, ShipsTheSixPowdersWithEverySourcedProperty) {
  const auto materials = bed::shipped_materials();
  std::set<std::string> names;
  for (const auto& m : materials) names.insert(m.name);
  EXPECT_EQ(names,
            (std::set<std::string>{"316L", "AlSi10Mg", "IN625", "IN718", "Ti-6Al-4V", "copper"}));
  for (const auto& m : materials) {
    EXPECT_FALSE(m.description.empty()) << m.name;
    for (const auto& key : bed::kMaterialKeys) {
      EXPECT_TRUE(m.get(key.key).has_value()) << m.name << " lacks " << key.key;
    }
    for (const auto& p : m.properties) EXPECT_FALSE(p.source.empty()) << m.name << " " << p.key;
    ASSERT_GE(m.solid.size(), 2u) << m.name;
    ASSERT_TRUE(m.liquid.has_value()) << m.name;
    for (const auto& row : m.solid)
      EXPECT_FALSE(row.source.empty()) << m.name << " " << row.temperature;
    EXPECT_FALSE(m.liquid->source.empty()) << m.name;
    // One powder, one density: the scalar is the table's first (room-temperature) row, to the
    // rounding of the sources (0.5 %).
    EXPECT_NEAR(*m.get("density"), m.solid.front().density, 5e-3 * m.solid.front().density)
        << m.name;
    // Metals expand on melting: the liquid is lighter than the hottest solid row.
    EXPECT_LT(m.liquid->density, m.solid.back().density) << m.name;
    // sinter holds the table from hold_from to the melting window: it lies between them.
    EXPECT_GE(*m.get("hold_from"), m.solid.back().temperature) << m.name;
    EXPECT_LT(*m.get("hold_from"), *m.get("melting_point")) << m.name;
  }
}

TEST(MaterialFile, NamesResolveToTheShippedFolderAndPathsStayPaths) {
  EXPECT_EQ(bed::material_path("copper", "--material"), bed::materials_folder() + "/copper.csv");
  EXPECT_EQ(bed::material_path("my/steel.csv", "--material"), "my/steel.csv");
  EXPECT_EQ(bed::material_path("steel.csv", "--material"), "steel.csv");
  try {
    bed::material_path("unobtainium", "--material");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("--material: 'unobtainium'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Ti-6Al-4V"), std::string::npos) << msg;  // the accepted names listed
  }
}

TEST(MaterialFile, ConductivityIsTheTableInterpolatedAndHeld) {
  const auto m = bed::read_material_file(bed::material_path("316L", "--material"));
  EXPECT_DOUBLE_EQ(m.solid_conductivity(200), 13.3);   // held below the table
  EXPECT_DOUBLE_EQ(m.solid_conductivity(2000), 26.2);  // held above it
  EXPECT_NEAR(m.solid_conductivity(329.5), 0.5 * (13.3 + 14.3), 1e-12);
}

TEST(MaterialFile, ATableWithoutPropertiesStillReads) {
  const TempFile file("bare", kTable);
  const auto m = bed::read_material_file(file.path());
  EXPECT_TRUE(m.properties.empty());
  EXPECT_EQ(m.solid.size(), 2u);
  EXPECT_EQ(m.name, std::filesystem::path(file.path()).stem().string());
}

TEST(MaterialFile, RefusesBadProperties) {
  expect_refused("unknown", "youngs,193e9,Pa,x\n", "unknown property 'youngs'");
  expect_refused("unit", "density,7.952,g/cm^3,x\n", "accepted: kg/m^3");
  expect_refused("range", "poisson_ratio,0.6,1,x\n", "out of range");
  expect_refused("nan", "density,abc,kg/m^3,x\n", "density 'abc'");
  expect_refused("twice", "density,7952,kg/m^3,x\ndensity,7952,kg/m^3,x\n", "given twice");
  expect_refused("short", "density,7952\n", "density,value,kg/m^3,source");
  expect_refused("melting", "solidus,1658,K,x\nliquidus,1723,K,x\nmelting_point,1600,K,x\n",
                 "melting_point below solidus");
  expect_refused("boiling", "melting_point,1700,K,x\nboiling_point,1600,K,x\n",
                 "boiling_point not above melting_point");
  expect_refused("after_table", std::string(kTable) + "density,7952,kg/m^3,x\n", "fields");
}
