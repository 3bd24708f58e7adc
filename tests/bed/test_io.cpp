// Bed file I/O (docs/bed-format.md): round trips, foreign formats, refusal of bad input
// with one line naming file and field, and atomic writes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"
#include "powderbed/bed/random.hpp"
#include "h5_edit.hpp"

namespace powderbed::bed {
namespace {

namespace fs = std::filesystem;
using test::H5Edit;

class BedIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("powderbed_test_io_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Every file name in the test folder (to see that no temporary is left behind).
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

// A bed with every optional field, non-trivial values and provenance (seed 42, 200 particles).
Bed full_bed() {
  Rng rng(42);
  Bed bed;
  bed.domain.lower = {-1e-3, 0.0, 1e-4};
  bed.domain.upper = {1e-3, 2e-3, 3e-3};
  bed.domain.periodic = {true, false, true};
  for (int i = 0; i < 200; ++i) {
    bed.x.push_back(uniform(rng, -1e-3, 1e-3));
    bed.y.push_back(uniform(rng, 0.0, 2e-3));
    bed.z.push_back(uniform(rng, 1e-4, 3e-3));
    bed.radius.push_back(uniform(rng, 5e-6, 4e-5));
    bed.id.push_back(1000000000000ull + 7ull * static_cast<std::uint64_t>(i));
    bed.vx.push_back(uniform(rng, -1, 1));
    bed.vy.push_back(uniform(rng, -1, 1));
    bed.vz.push_back(-1.0 / 3.0);
    bed.material.push_back(static_cast<std::uint16_t>(i % 3));
    bed.temperature.push_back(uniform(rng, 293.15, 1700.0));
    bed.phase.push_back(static_cast<std::uint8_t>(i % 3));
  }
  bed.provenance.created_by = "test_io 0.1.0";
  bed.provenance.command_line = "packgen --seed 18446744073709551615 --out 'a b.h5'";
  bed.provenance.rng_seed = std::numeric_limits<std::uint64_t>::max();
  bed.provenance.stage = "deposit";
  bed.provenance.scene = "[psd]\nkind = lognormal\nd50 = 3.0e-05 ; m\n\n[laser]\npower = 200\n";
  return bed;
}

// Runs `f`, expects InputError whose one-line message contains every `parts` string.
void expect_input_error(const std::function<void()>& f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "not one line: " << msg;
    for (const auto& part : parts) EXPECT_NE(msg.find(part), std::string::npos) << msg;
  }
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<double> rows_of(const Bed& bed) {
  std::vector<double> rows;
  for (std::size_t i = 0; i < bed.n(); ++i) rows.insert(rows.end(), {bed.x[i], bed.y[i], bed.z[i]});
  return rows;
}

// --- round trips -------------------------------------------------------------------------------

TEST_F(BedIo, H5RoundTripIsBitExactForEveryField) {
  const Bed bed = full_bed();
  write_bed_h5(bed, path("bed.h5"));
  const Bed back = read_bed_h5(path("bed.h5"));
  // Exact equality throughout: the file stores the same IEEE doubles and integers.
  EXPECT_EQ(back.domain.dimension, 3);
  EXPECT_EQ(back.domain.lower, bed.domain.lower);
  EXPECT_EQ(back.domain.upper, bed.domain.upper);
  EXPECT_EQ(back.domain.periodic, bed.domain.periodic);
  EXPECT_EQ(back.x, bed.x);
  EXPECT_EQ(back.y, bed.y);
  EXPECT_EQ(back.z, bed.z);
  EXPECT_EQ(back.radius, bed.radius);
  EXPECT_EQ(back.id, bed.id);
  EXPECT_EQ(back.vx, bed.vx);
  EXPECT_EQ(back.vy, bed.vy);
  EXPECT_EQ(back.vz, bed.vz);
  EXPECT_EQ(back.material, bed.material);
  EXPECT_EQ(back.temperature, bed.temperature);
  EXPECT_EQ(back.phase, bed.phase);
  EXPECT_EQ(back.provenance.created_by, bed.provenance.created_by);
  EXPECT_EQ(back.provenance.command_line, bed.provenance.command_line);
  EXPECT_EQ(back.provenance.rng_seed, bed.provenance.rng_seed);
  EXPECT_EQ(back.provenance.stage, bed.provenance.stage);
  EXPECT_EQ(back.provenance.scene, bed.provenance.scene);
  EXPECT_EQ(files(), (std::vector<std::string>{"bed.h5", "bed.xmf"}));
}

TEST_F(BedIo, H5WithoutOptionalFieldsReadsThemEmpty) {
  Bed bed = hexagonal_lattice_2d(4, 2, 1e-5);
  write_bed_h5(bed, path("hex.h5"));
  const Bed back = read_bed_h5(path("hex.h5"));
  EXPECT_EQ(back.domain.dimension, 2);
  EXPECT_EQ(back.domain.periodic, bed.domain.periodic);
  EXPECT_EQ(back.x, bed.x);
  EXPECT_EQ(back.z, bed.z);
  EXPECT_EQ(back.provenance.stage, "lattice");
  EXPECT_TRUE(back.provenance.created_by.empty());
  EXPECT_FALSE(back.has_velocity());
  EXPECT_TRUE(back.material.empty());
  EXPECT_TRUE(back.temperature.empty());
  EXPECT_TRUE(back.phase.empty());
}

TEST_F(BedIo, XdmfSidecarNamesTheH5FileOnlyAndListsFields) {
  write_bed_h5(full_bed(), path("bed.h5"));
  const std::string xmf = slurp(path("bed.xmf"));
  EXPECT_NE(xmf.find("TopologyType=\"Polyvertex\" NumberOfElements=\"200\""), std::string::npos);
  EXPECT_NE(xmf.find("GeometryType=\"XYZ\""), std::string::npos);
  EXPECT_NE(xmf.find(">bed.h5:/particles/position<"), std::string::npos);
  for (const char* field : {"radius", "id", "material", "velocity", "temperature", "phase"})
    EXPECT_NE(xmf.find(std::string("Name=\"") + field + "\""), std::string::npos) << field;
  EXPECT_EQ(xmf.find(dir_.string()), std::string::npos) << "the pair must stay movable";
}

TEST_F(BedIo, CsvRoundTripKeepsFullPrecision) {
  const Bed bed = full_bed();
  write_bed_csv(bed, path("bed.csv"));
  EXPECT_EQ(slurp(path("bed.csv")).substr(0, 8), "x,y,z,r\n");
  const Bed back = read_bed_csv(path("bed.csv"), bed.domain);
  // %.17g text reads back to the identical double, so equality is exact.
  EXPECT_EQ(back.x, bed.x);
  EXPECT_EQ(back.y, bed.y);
  EXPECT_EQ(back.z, bed.z);
  EXPECT_EQ(back.radius, bed.radius);
  EXPECT_EQ(back.domain.periodic, bed.domain.periodic);
}

TEST_F(BedIo, H5ToCsvToH5KeepsEveryParticle) {
  const Bed bed = fcc_lattice(3, 1e-5);  // 108 particles
  write_bed_h5(bed, path("a.h5"));
  write_bed_any(read_bed_any(path("a.h5")), path("a.csv"));
  write_bed_any(read_bed_any(path("a.csv"), &bed.domain), path("b.h5"));
  const Bed back = read_bed_h5(path("b.h5"));
  ASSERT_EQ(back.n(), 108u);
  EXPECT_EQ(back.x, bed.x);
  EXPECT_EQ(back.y, bed.y);
  EXPECT_EQ(back.z, bed.z);
  EXPECT_EQ(back.radius, bed.radius);
}

TEST_F(BedIo, CsvIn2dDomainNeedsZeroZ) {
  Domain flat;
  flat.dimension = 2;
  flat.upper = {1, 1, 0};
  std::ofstream(path("flat.csv")) << "x,y,z,r\n0.5,0.5,0,0.1\n0.2,0.2,0.25,0.1\n";
  expect_input_error([&] { read_bed_csv(path("flat.csv"), flat); },
                     {path("flat.csv") + ":3:", "z is 0.25", "2D"});
}

// --- LAMMPS ------------------------------------------------------------------------------------

TEST_F(BedIo, DumpImportReadsTheLastSnapshot) {
  const Bed bed = read_lammps_dump(POWDERBED_TEST_DATA "/sample.dump");
  ASSERT_EQ(bed.n(), 3u);
  EXPECT_EQ(bed.domain.dimension, 3);
  EXPECT_EQ(bed.domain.lower, (std::array<double, 3>{0, -0.001, 0}));
  EXPECT_EQ(bed.domain.upper, (std::array<double, 3>{0.001, 0.001, 0.004}));
  EXPECT_EQ(bed.domain.periodic, (std::array<bool, 3>{true, true, false}));  // pp pp fm
  EXPECT_EQ(bed.id, (std::vector<std::uint64_t>{6, 2, 4}));  // LAMMPS id - 1
  EXPECT_EQ(bed.radius, (std::vector<double>{0.00005, 0.000025, 0.0000375}));  // diameter / 2
  // Scaled xs, ys: lo + s (hi - lo) rounds twice, hence a few ulps (EXPECT_DOUBLE_EQ: 4 ulps).
  const double x[] = {0.00025, 0.00075, 0.0005};
  const double y[] = {0.0, -0.0005, 0.0005};
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(bed.x[i], x[i]);
    EXPECT_DOUBLE_EQ(bed.y[i], y[i]);
  }
  EXPECT_EQ(bed.z, (std::vector<double>{0.000125, 0.0003, 0.0005}));  // unscaled: exact
  EXPECT_EQ(bed.vx, (std::vector<double>{0, 0.125, 0}));
  EXPECT_EQ(bed.vy, (std::vector<double>{0, 0, -0.25}));
  EXPECT_EQ(bed.vz, (std::vector<double>{-0.5, 0, 0}));
}

TEST_F(BedIo, DumpWithShortAtomLineNamesFileAndLine) {
  std::ofstream(path("bad.dump")) << "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n2\n"
                                     "ITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\n"
                                     "ITEM: ATOMS id type x y z radius\n"
                                     "1 1 0.5 0.5 0.5 0.1\n2 1 0.2 0.2 0.1\n";
  expect_input_error([&] { read_lammps_dump(path("bad.dump")); },
                     {path("bad.dump") + ":11:", "5 columns, expected 6"});
}

TEST_F(BedIo, LammpsDataIsReadByLmpAndItsDumpReadsBack) {
  if (std::system("command -v lmp > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "lmp (Debian package lammps) not on PATH";
  Bed bed = simple_cubic_lattice(3, 2.5e-5);  // 27 particles in [0, 1.5e-4]^3
  bed.add(1.5e-4, 0.75e-4, 0.75e-4, 2.5e-5);  // a centre on the upper x face: the box widens
  write_lammps_data(bed, path("bed.data"), 7952.0);
  std::ofstream(path("deck.in"))
      << "units si\natom_style sphere\ndimension 3\nboundary f f f\n"
      << "read_data bed.data\n"
      << "variable n equal atoms\nprint \"N=${n}\"\n"
      << "write_dump all custom lmp.dump id type x y z radius modify format float %.17g\n";
  const std::string command =
      "cd '" + dir_.string() + "' && lmp -in deck.in -log none > lmp.out 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << slurp(path("lmp.out"));
  EXPECT_NE(slurp(path("lmp.out")).find("N=28"), std::string::npos) << slurp(path("lmp.out"));

  // LAMMPS's own dump of what it read: same ids, centres and radii (printed with %.17g, so exact).
  const Bed back = read_lammps_dump(path("lmp.dump"));
  ASSERT_EQ(back.n(), 28u);
  for (std::size_t k = 0; k < back.n(); ++k) {
    const std::size_t i = back.id[k];  // simple_cubic_lattice ids are 0..n-1, in order
    ASSERT_LT(i, bed.n());
    EXPECT_EQ(back.x[k], bed.x[i]);
    EXPECT_EQ(back.y[k], bed.y[i]);
    EXPECT_EQ(back.z[k], bed.z[i]);
    EXPECT_EQ(back.radius[k], bed.radius[i]);
  }
  EXPECT_LT(back.domain.upper[0], 1.5e-4 * (1 + 1e-8)) << "padding is 1e-9 of the length";
  EXPECT_GT(back.domain.upper[0], 1.5e-4);
}

TEST_F(BedIo, LammpsDataLayout) {
  write_lammps_data(hexagonal_lattice_2d(4, 2, 1e-5), path("hex.data"), 4430.0);
  const std::string data = slurp(path("hex.data"));
  EXPECT_NE(data.find("\n8 atoms\n1 atom types\n"), std::string::npos);
  EXPECT_NE(data.find("-1.0000000000000001e-05 1.0000000000000001e-05 zlo zhi"),
            std::string::npos) << "2D: a slab of +-r_max";
  EXPECT_NE(data.find("Atoms # sphere\n\n1 1 2.0000000000000002e-05 4430 "), std::string::npos)
      << "id + 1, type 1, diameter, density";
  // LAMMPS atom ids are 32-bit in its default build.
  expect_input_error([&] { write_lammps_data(full_bed(), path("big.data")); },
                     {"big.data", "id 1000000000000", "LAMMPS"});
}

// --- bad input ---------------------------------------------------------------------------------

TEST_F(BedIo, RefusesNonHdf5File) {
  std::ofstream(path("text.h5")) << "x,y,z,r\n";
  expect_input_error([&] { read_bed_h5(path("text.h5")); }, {path("text.h5"), "not an HDF5 file"});
}

TEST_F(BedIo, RefusesMissingRadius) {
  write_bed_h5(simple_cubic_lattice(2, 1e-5), path("bed.h5"));
  H5Edit(path("bed.h5")).remove("/particles/radius");
  expect_input_error([&] { read_bed_h5(path("bed.h5")); },
                     {path("bed.h5"), "/particles/radius", "missing"});
}

TEST_F(BedIo, RefusesRadiusWithOneRowTooFew) {
  write_bed_h5(simple_cubic_lattice(2, 1e-5), path("bed.h5"));  // 8 particles
  H5Edit(path("bed.h5")).replace("/particles/radius", std::vector<double>(7, 1e-5), 0);
  expect_input_error([&] { read_bed_h5(path("bed.h5")); },
                     {path("bed.h5"), "/particles/radius", "7 rows", "8"});
}

TEST_F(BedIo, RefusesPositionOfWrongShape) {
  write_bed_h5(simple_cubic_lattice(2, 1e-5), path("bed.h5"));
  H5Edit(path("bed.h5")).replace("/particles/position", std::vector<double>(16, 1e-5), 2);
  expect_input_error([&] { read_bed_h5(path("bed.h5")); },
                     {path("bed.h5"), "/particles/position", "wrong shape", "8 x 2"});
}

TEST_F(BedIo, RefusesNanPosition) {
  const Bed bed = simple_cubic_lattice(2, 1e-5);
  write_bed_h5(bed, path("bed.h5"));
  std::vector<double> rows = rows_of(bed);
  rows[3 * 5 + 1] = std::numeric_limits<double>::quiet_NaN();  // y of particle 5
  H5Edit(path("bed.h5")).replace("/particles/position", rows, 3);
  expect_input_error([&] { read_bed_h5(path("bed.h5")); }, {path("bed.h5"), "position y[5]", "nan"});
}

TEST_F(BedIo, RefusesNegativeRadius) {
  Bed bed = simple_cubic_lattice(2, 1e-5);
  write_bed_h5(bed, path("bed.h5"));
  bed.radius[3] = -1e-5;
  H5Edit(path("bed.h5")).replace("/particles/radius", bed.radius, 0);
  expect_input_error([&] { read_bed_h5(path("bed.h5")); }, {path("bed.h5"), "radius[3]", "> 0"});
}

TEST_F(BedIo, RefusesNewerFormatVersion) {
  write_bed_h5(simple_cubic_lattice(2, 1e-5), path("bed.h5"));
  H5Edit(path("bed.h5")).set_int_attr("version", 2);
  expect_input_error([&] { read_bed_h5(path("bed.h5")); },
                     {path("bed.h5"), "version 2", "newer", "accepted: 1"});
}

TEST_F(BedIo, ReadsFixedLengthStringsAndRefusesOtherFormats) {
  write_bed_h5(simple_cubic_lattice(2, 1e-5), path("bed.h5"));
  H5Edit(path("bed.h5")).set_fixed_string_attr("format", "powderbed.bed");
  EXPECT_EQ(read_bed_h5(path("bed.h5")).n(), 8u);
  H5Edit(path("bed.h5")).set_fixed_string_attr("format", "other.bed");
  expect_input_error([&] { read_bed_h5(path("bed.h5")); },
                     {path("bed.h5"), "format is 'other.bed'", "powderbed.bed"});
}

TEST_F(BedIo, RefusesCsvLineWithThreeFields) {
  std::ofstream(path("bed.csv")) << "x,y,z,r\n0.5,0.5,0.5,0.1\n0.1,0.2,0.3\n";
  expect_input_error([&] { read_bed_csv(path("bed.csv"), Domain{}); },
                     {path("bed.csv") + ":3:", "3 fields, expected 4"});
}

TEST_F(BedIo, RefusesUnknownExtensionListingAccepted) {
  expect_input_error([&] { read_bed_any(path("bed.xyz")); }, {"bed.xyz", ".h5", ".csv", ".dump"});
  expect_input_error([&] { write_bed_any(full_bed(), path("bed.xyz")); },
                     {"bed.xyz", ".h5", ".csv", ".data"});
  expect_input_error([&] { read_bed_any(path("bed.csv")); }, {"bed.csv", "no domain"});
}

// --- atomic writes -----------------------------------------------------------------------------

TEST_F(BedIo, WriteIntoMissingFolderThrowsAndLeavesNoTemporary) {
  const std::string target = path("no/such/folder/bed.h5");
  expect_input_error([&] { write_bed_h5(full_bed(), target); }, {target, "No such file"});
  expect_input_error([&] { write_bed_csv(full_bed(), path("nope/bed.csv")); }, {"nope/bed.csv"});
  EXPECT_TRUE(files().empty());
}

TEST_F(BedIo, FailedOverwriteKeepsTheOldBed) {
  write_bed_h5(full_bed(), path("bed.h5"));
  const std::string before = slurp(path("bed.h5"));
  Bed bad = simple_cubic_lattice(2, 1e-5);
  bad.radius[1] = std::numeric_limits<double>::infinity();
  expect_input_error([&] { write_bed_h5(bad, path("bed.h5")); }, {path("bed.h5"), "radius[1]"});
  EXPECT_EQ(slurp(path("bed.h5")), before);
  EXPECT_EQ(read_bed_h5(path("bed.h5")).n(), 200u);
  EXPECT_EQ(files(), (std::vector<std::string>{"bed.h5", "bed.xmf"}));
}

TEST_F(BedIo, FailedRenameRemovesTheTemporary) {
  // The target is a non-empty folder: the whole temporary file is written, the rename fails.
  fs::create_directories(path("taken.h5/inside"));
  expect_input_error([&] { write_bed_h5(full_bed(), path("taken.h5")); },
                     {path("taken.h5"), "cannot replace"});
  EXPECT_TRUE(fs::is_directory(path("taken.h5/inside")));
  EXPECT_EQ(files(), (std::vector<std::string>{"taken.h5"}));
}

}  // namespace
}  // namespace powderbed::bed
