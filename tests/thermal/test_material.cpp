// Material tables (docs/physics.md §5, material.hpp): the 316L file of [GZ] Table 1 loads with the
// values of [GZ] Table 1; malformed tables are refused with InputError naming file and line.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

#include "powderbed/bed/errors.hpp"
#include "powderbed/thermal/material.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;

namespace {

// A table file under /tmp, removed when the test ends.
class TempTable {
 public:
  TempTable(const std::string& name, const std::string& text)
      : path_("/tmp/powderbed_thermal_" + std::to_string(::getpid()) + "_" + name + ".csv") {
    std::ofstream(path_) << text;
  }
  ~TempTable() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

const char* kHeader =
    "temperature_K,specific_heat_J_per_kgK,conductivity_W_per_mK,density_kg_per_m3,phase\n";

// Expects InputError whose message names the file and contains `what`.
void expect_refused(const std::string& name, const std::string& body, const std::string& what) {
  const TempTable file(name, std::string(kHeader) + body);
  try {
    thermal::read_material_table(file.path());
    ADD_FAILURE() << name << ": accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file.path()), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  }
}

}  // namespace

TEST(MaterialTable, Reads316L) {
  const auto t = test::table_316l();
  ASSERT_EQ(t.temperature.size(), 10u);
  EXPECT_EQ(t.temperature.front(), 293);
  EXPECT_EQ(t.temperature.back(), 1255);
  EXPECT_EQ(t.specific_heat.front(), 452);
  EXPECT_EQ(t.conductivity.back(), 26.2);
  EXPECT_EQ(t.density[4], 7786);
  EXPECT_EQ(t.liquid_specific_heat, 815);
  EXPECT_EQ(t.liquid_conductivity, 32.4);
  EXPECT_EQ(t.liquid_density, 7300);
}

TEST(MaterialTable, RefusesMalformedTables) {
  expect_refused("decreasing", "293,452,13.3,7952,solid\n366,485,14.3,7919,solid\n"
                               "300,527,15.9,7877,solid\n1700,815,32.4,7300,liquid\n",
                 "does not increase");
  expect_refused("repeated", "293,452,13.3,7952,solid\n293,485,14.3,7919,solid\n"
                             "1700,815,32.4,7300,liquid\n",
                 "does not increase");
  expect_refused("negative", "293,452,13.3,7952,solid\n366,-485,14.3,7919,solid\n"
                             "1700,815,32.4,7300,liquid\n",
                 "specific heat");
  expect_refused("no_liquid", "293,452,13.3,7952,solid\n366,485,14.3,7919,solid\n",
                 "no liquid row");
  expect_refused("one_solid", "293,452,13.3,7952,solid\n1700,815,32.4,7300,liquid\n",
                 "1 solid rows");
  expect_refused("not_a_number", "293,452,13.3,7952,solid\n366,485,abc,7919,solid\n"
                                 "1700,815,32.4,7300,liquid\n",
                 "conductivity");
  expect_refused("short_row", "293,452,13.3,7952,solid\n366,485,14.3,solid\n"
                              "1700,815,32.4,7300,liquid\n",
                 "4 fields");
  expect_refused("phase", "293,452,13.3,7952,solid\n366,485,14.3,7919,gas\n"
                          "1700,815,32.4,7300,liquid\n",
                 "phase 'gas'");
  expect_refused("solid_after_liquid", "293,452,13.3,7952,solid\n1700,815,32.4,7300,liquid\n"
                                       "366,485,14.3,7919,solid\n",
                 "after the liquid row");
  EXPECT_THROW(thermal::read_material_table("/tmp/powderbed_thermal_no_such_table.csv"),
               InputError);
}

// docs/physics.md §5: linear interpolation, linear extrapolation from the last two rows to 1400 K,
// held to the melting window, liquid values beyond it ([GZ]: K stays solid in the liquid).
TEST(Material, InterpolatesExtrapolatesAndHolds) {
  const thermal::Material m(test::table_316l(), thermal::PhaseChange{}, 1400,
                            thermal::LiquidConductivity::solid);
  EXPECT_DOUBLE_EQ(m.solid_specific_heat(200), 452);           // held below the table
  EXPECT_DOUBLE_EQ(m.solid_specific_heat(329.5), 0.5 * (452 + 485));
  const double k1400 = 24.6 + (26.2 - 24.6) * (1400 - 1144) / (1255.0 - 1144);
  EXPECT_NEAR(m.solid_conductivity(1400), k1400, 1e-12 * k1400);  // round-off of the blend
  EXPECT_NEAR(m.solid_conductivity(1650), k1400, 1e-12 * k1400);
  EXPECT_NEAR(m.conductivity(2000), k1400, 1e-12 * k1400);        // solid K in the liquid
  EXPECT_DOUBLE_EQ(m.density(2000), 7300);
  EXPECT_DOUBLE_EQ(m.apparent_heat_capacity(2000), 815);
  // Across the melting window K and rho blend linearly: the middle is the mean.
  EXPECT_NEAR(m.density(1700), 0.5 * (m.solid_density(1690) + 7300), 1e-9);
  const thermal::Material liquid_k(test::table_316l(), thermal::PhaseChange{}, 1400,
                                   thermal::LiquidConductivity::table);
  EXPECT_DOUBLE_EQ(liquid_k.conductivity(2000), 32.4);
  EXPECT_EQ(m.phase(1699.9), 0u);
  EXPECT_EQ(m.phase(1700), 1u);
  EXPECT_EQ(m.phase(3130), 2u);
}

TEST(Material, RefusesInconsistentPhaseChange) {
  const auto table = test::table_316l();
  const auto make = [&](thermal::PhaseChange p, double hold) {
    thermal::Material m(table, p, hold, thermal::LiquidConductivity::solid);
  };
  thermal::PhaseChange p;
  p.window = 0;
  EXPECT_THROW(make(p, 1400), InputError);
  p = {};
  p.boiling_point = 1710;  // windows overlap
  EXPECT_THROW(make(p, 1400), InputError);
  p = {};
  p.melting_point = 1200;  // below the last table row
  EXPECT_THROW(make(p, 1255), InputError);
  p = {};
  EXPECT_THROW(make(p, 1000), InputError);  // hold below the last table row
  EXPECT_THROW(make(p, 1695), InputError);  // hold inside the melting window
  p.latent_melt = -1;
  EXPECT_THROW(make(p, 1400), InputError);
}
