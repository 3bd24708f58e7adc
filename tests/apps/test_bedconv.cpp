// bedconv end to end (docs/architecture.md "Command-line programs"): converts by extension, refuses bad
// input with exit status 2 and one line on stderr.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

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

TEST_F(Bedconv, HelpListsOptionsWithUnits) {
  const auto r = run_app("bedconv", "--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--density"), std::string::npos);
  EXPECT_NE(r.out.find("kg/m^3"), std::string::npos);
  EXPECT_NE(r.out.find("--domain"), std::string::npos);
}

}  // namespace
