// bedconv end to end (docs/architecture.md "Command-line programs"): converts by extension, refuses bad
// input with exit status 2 and one line on stderr.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"
#include "run_command.hpp"

namespace {

namespace fs = std::filesystem;
namespace bed = powderbed::bed;
using powderbed::test::read_text;
using powderbed::test::run_app;

class Bedconv : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("powderbed_test_bedconv_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    bed::write_bed_h5(bed::simple_cubic_lattice(3, 1e-5), path("in.h5"));  // 27 particles
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

TEST_F(Bedconv, ConvertsH5ToCsvAndBack) {
  auto r = run_app("bedconv", path("in.h5") + " " + path("bed.csv"));
  ASSERT_EQ(r.status, 0) << r.err;
  r = run_app("bedconv", path("bed.csv") + " " + path("back.h5") + " --domain 0,0,0,6e-5,6e-5,6e-5");
  ASSERT_EQ(r.status, 0) << r.err;
  const bed::Bed back = bed::read_bed_h5(path("back.h5"));
  EXPECT_EQ(back.n(), 27u);
  EXPECT_EQ(back.x, bed::simple_cubic_lattice(3, 1e-5).x);  // %.17g CSV: exact
  EXPECT_EQ(back.provenance.created_by.rfind("bedconv ", 0), 0u) << back.provenance.created_by;
  EXPECT_NE(back.provenance.command_line.find("--domain"), std::string::npos);
}

TEST_F(Bedconv, WritesLammpsDataWithTheGivenDensity) {
  const auto r = run_app("bedconv", path("in.h5") + " " + path("bed.data") + " --density 4430");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string data = read_text(path("bed.data"));
  EXPECT_NE(data.find("27 atoms"), std::string::npos);
  EXPECT_NE(data.find(" 4430 "), std::string::npos) << "density column";
}

TEST_F(Bedconv, CsvWithoutDomainExits2WithOneLine) {
  ASSERT_EQ(run_app("bedconv", path("in.h5") + " " + path("bed.csv")).status, 0);
  const auto r = run_app("bedconv", path("bed.csv") + " " + path("back.h5"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("bed.csv: CSV carries no domain; give --domain"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("back.h5")));
}

TEST_F(Bedconv, NonHdf5InputExits2NamingTheFile) {
  std::ofstream(path("fake.h5")) << "not hdf5\n";
  const auto r = run_app("bedconv", path("fake.h5") + " " + path("out.csv"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_EQ(r.err.rfind("bedconv: " + path("fake.h5") + ": not an HDF5 file", 0), 0u) << r.err;
  EXPECT_FALSE(fs::exists(path("out.csv")));
}

// --- decks and foreign formats (docs/decks.md) -------------------------------------------------

// A bed as deposit records it: its scene in /provenance (Ti-6Al-4V density, zeta 0.2).
void write_deposited(const std::string& file) {
  bed::Bed b = bed::simple_cubic_lattice(3, 1e-5);
  b.domain.periodic = {true, true, false};
  b.provenance.stage = "deposit";
  b.provenance.scene = "material.density = 4430\nmaterial.damping = 0.2\ncontact.law = hertz\n"
                       "gravity = 9.81\ndt = 2e-9\n";
  bed::write_bed_h5(b, file);
}

TEST_F(Bedconv, DeckTakesTheBedsSceneAndSaysWhereEachNumberCameFrom) {
  write_deposited(path("dep.h5"));
  const auto r = run_app("bedconv", path("dep.h5") + " " + path("dep.data") + " --deck lammps --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("in.dep.lammps"), std::string::npos) << r.out;
  const std::string deck = read_text(path("in.dep.lammps"));
  EXPECT_NE(deck.find("boundary       p p f"), std::string::npos);
  EXPECT_NE(deck.find("timestep       2.0000000000000001e-09"), std::string::npos) << "the scene's dt";
  EXPECT_NE(deck.find("zeta = 0.20000000000000001 (material.damping): " + path("dep.h5") +
                      " /provenance scene"), std::string::npos) << deck;
  // zeta 0.2 -> alpha(e) = 0.2 sqrt(6): e = 0.35982 (docs/results/deck-damping.md).
  EXPECT_NE(deck.find(" 0.3598"), std::string::npos) << deck;
  EXPECT_NE(read_text(path("dep.data")).find(" 4430 "), std::string::npos) << "the scene's density";
}

TEST_F(Bedconv, DeckOfALaterStageTakesTheContactAttributesNotItsScene) {
  bed::Bed b = bed::simple_cubic_lattice(3, 1e-5);
  b.provenance.stage = "sinter";
  b.provenance.scene = "dt = 5e-6\n";  // sinter's thermal step, no DEM step
  b.provenance.contact.law = "hertz";
  b.provenance.contact.young = 110e9;  // Ti-6Al-4V, softened 100 x in the DEM that made it
  b.provenance.contact.poisson = 0.31;
  b.provenance.contact.wall_young = 193e9;
  b.provenance.contact.wall_poisson = 0.26;
  b.provenance.contact.young_scale = 100;
  bed::write_bed_h5(b, path("hot.h5"));
  const auto r = run_app("bedconv", path("hot.h5") + " " + path("hot.data") + " --deck liggghts");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string deck = read_text(path("in.hot.liggghts"));
  // E / S for the particles (1.1e9 Pa) and the walls (1.93e9 Pa), in that order.
  EXPECT_NE(deck.find("youngsModulus peratomtype 1100000000 1930000000\n"), std::string::npos) << deck;
  EXPECT_NE(deck.find("contact_* attributes"), std::string::npos);
  EXPECT_EQ(deck.find("timestep       5"), std::string::npos) << "not sinter's step";
}

TEST_F(Bedconv, DeckSceneOverridesAndBadDeckInputsExit2WritingNothing) {
  write_deposited(path("dep.h5"));
  std::ofstream(path("wet.ini")) << "[material]\ndamping = 0.7\n";
  auto r = run_app("bedconv", path("dep.h5") + " " + path("d.data") + " --deck lammps --deck-scene " +
                   path("wet.ini"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("zeta 0.7"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("d.data")));
  EXPECT_FALSE(fs::exists(path("in.d.lammps")));
  r = run_app("bedconv", path("dep.h5") + " " + path("d.data") + " --deck gromacs");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--deck: 'gromacs' (accepted: lammps, liggghts)"), std::string::npos) << r.err;
  r = run_app("bedconv", path("dep.h5") + " " + path("d.h5") + " --deck lammps");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(".data"), std::string::npos) << r.err;
}

TEST_F(Bedconv, MultiSnapshotDumpBecomesATrajectory) {
  std::ofstream(path("run.lammpstrj"))
      << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 1e-3\n0 1e-3\n0 1e-3\n"
      << "ITEM: ATOMS id x y z vx vy vz radius\n1 5e-4 5e-4 5e-4 0 0 -1 2e-5\n"
      << "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 1e-3\n0 1e-3\n0 1e-3\n"
      << "ITEM: ATOMS id x y z vx vy vz radius\n1 5e-4 5e-4 4.9e-4 0 0 -1 2e-5\n";
  auto r = run_app("bedconv", path("run.lammpstrj") + " " + path("t.h5") + " --all-snapshots");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--dt"), std::string::npos) << "no ITEM: TIME: " << r.err;
  r = run_app("bedconv", path("run.lammpstrj") + " " + path("t.h5") + " --all-snapshots --dt 1e-7 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"snapshots\":2"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(path("t.xmf")));
}

// A dump without ITEM: TIME (LIGGGHTS 3.8 writes none) beside the deck bedconv wrote for it: the
// snapshots' times are the steps times the deck's timestep, without --dt; a deck that names
// another dump does not count.
TEST_F(Bedconv, DumpTakesItsTimeStepFromTheDeckThatWroteIt) {
  std::ofstream(path("run.liggghts.lammpstrj"))
      << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 1e-3\n0 1e-3\n0 1e-3\n"
      << "ITEM: ATOMS id x y z vx vy vz radius\n1 5e-4 5e-4 5e-4 0 0 -1 2e-5\n"
      << "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 1e-3\n0 1e-3\n0 1e-3\n"
      << "ITEM: ATOMS id x y z vx vy vz radius\n1 5e-4 5e-4 4.9e-4 0 0 -1 2e-5\n";
  std::ofstream(path("in.other.liggghts")) << "variable DUMP       index other.liggghts.lammpstrj\n"
                                           << "timestep       1e-9\n";
  const std::string args = path("run.liggghts.lammpstrj") + " " + path("t.h5") + " --all-snapshots";
  auto r = run_app("bedconv", args);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--dt"), std::string::npos) << r.err;
  std::ofstream(path("in.run.liggghts")) << "variable DUMP       index run.liggghts.lammpstrj\n"
                                         << "timestep       2.5e-09\n";
  r = run_app("bedconv", args);
  ASSERT_EQ(r.status, 0) << r.err;
  const hid_t file = H5Fopen(path("t.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  double time = -1;
  const hid_t attr = H5Aopen_by_name(file, bed::step_group(100).c_str(), "time", H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(attr, 0);
  H5Aread(attr, H5T_NATIVE_DOUBLE, &time);
  H5Aclose(attr);
  H5Fclose(file);
  EXPECT_DOUBLE_EQ(time, 100 * 2.5e-9);
  // --dt, when given, wins over the deck.
  r = run_app("bedconv", args + " --dt 1e-7");
  ASSERT_EQ(r.status, 0) << r.err;
}

TEST_F(Bedconv, CoarseDumpWarnsOnStderrAndStillConverts) {
  std::ofstream(path("g.dump"))
      << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n0 0.001\n0 0.001\n0 0.001\n"
      << "ITEM: ATOMS id x y z radius\n1 0.000412345 0.0005 0.0005 2.13457e-05\n"
      << "2 0.000454036 0.0005 0.0005 2.03457e-05\n";
  auto r = run_app("bedconv", path("g.dump") + " " + path("g.h5"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("warning: " + path("g.dump") + ": printed with 6 significant digits"),
            std::string::npos) << r.err;
  // At a tolerance of 0.1 (4e-6 m) the 6 digits (gaps off by ~2e-9 m) are enough.
  r = run_app("bedconv", path("g.dump") + " " + path("g2.h5") + " --tol 0.1");
  EXPECT_EQ(r.err, "");
}

TEST_F(Bedconv, HelpListsOptionsWithUnits) {
  const auto r = run_app("bedconv", "--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--density"), std::string::npos);
  EXPECT_NE(r.out.find("kg/m^3"), std::string::npos);
  EXPECT_NE(r.out.find("--domain"), std::string::npos);
}

}  // namespace
