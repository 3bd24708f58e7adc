// Bad input at the command line (issue 2): each bad file or option makes bedstat exit 2 with one
// line on stderr naming the file, dataset or option, and nothing on stdout.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "h5_edit.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"
#include "run_command.hpp"

namespace {

using powderbed::test::CommandResult;
using powderbed::test::H5Edit;
using powderbed::test::run_app;

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = powderbed::test::scratch_dir("bad_input");
    bed_ = powderbed::bed::simple_cubic_lattice(2, 1e-5);  // 8 particles
    powderbed::bed::write_bed_h5(bed_, path());
  }
  std::string path() const { return dir_ + "/bed.h5"; }

  // Exit 2, exactly one line on stderr containing every part, no JSON on stdout.
  static void expect_refused(const CommandResult& r, std::initializer_list<std::string> parts) {
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err_lines(), 1) << r.err;
    for (const auto& part : parts) EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }

  std::string dir_;
  powderbed::bed::Bed bed_;
};

TEST_F(BadInput, FileThatIsNotHdf5) {
  std::ofstream(path()) << "this is not a bed\n";
  expect_refused(run_app("bedstat", path() + " --json"), {path(), "not an HDF5 file"});
}

TEST_F(BadInput, MissingDataset) {
  H5Edit(path()).remove("/particles/id");
  expect_refused(run_app("bedstat", path() + " --json"), {path(), "/particles/id", "missing"});
}

TEST_F(BadInput, ParticleCountMismatch) {
  H5Edit(path()).replace("/particles/radius", std::vector<double>(7, 1e-5), 0);
  expect_refused(run_app("bedstat", path() + " --json"), {path(), "/particles/radius"});
}

TEST_F(BadInput, NanPosition) {
  std::vector<double> rows;
  for (std::size_t i = 0; i < bed_.n(); ++i) rows.insert(rows.end(), {bed_.x[i], bed_.y[i], bed_.z[i]});
  rows[3 * 2] = std::numeric_limits<double>::quiet_NaN();  // x of particle 2
  H5Edit(path()).replace("/particles/position", rows, 3);
  expect_refused(run_app("bedstat", path() + " --json"), {path(), "position x[2]", "nan"});
}

TEST_F(BadInput, NegativeRadius) {
  std::vector<double> radius = bed_.radius;
  radius[4] = -1e-5;
  H5Edit(path()).replace("/particles/radius", radius, 0);
  expect_refused(run_app("bedstat", path() + " --json"), {path(), "radius[4]", "> 0"});
}

TEST_F(BadInput, NewerMajorVersion) {
  H5Edit(path()).set_int_attr("version", 2);
  expect_refused(run_app("bedstat", path() + " --json"), {path(), "version 2"});
}

TEST_F(BadInput, PsdWithMinAboveMax) {
  expect_refused(run_app("bedstat", path() + " --json --psd gauss:mean=3e-5,sd=5e-6,min=4e-5,max=2e-5"),
                 {"--psd", "min"});
}

TEST_F(BadInput, PsdWithNegativeSd) {
  expect_refused(run_app("bedstat", path() + " --json --psd gauss:mean=3e-5,sd=-5e-6,min=2e-5,max=4e-5"),
                 {"--psd", "sd"});
}

TEST_F(BadInput, PsdWindowWithNoMass) {
  // 40 standard deviations above the mean: the normal has no representable mass there.
  expect_refused(run_app("bedstat", path() + " --json --psd gauss:mean=1e-5,sd=1e-7,min=5e-5,max=6e-5"),
                 {"--psd", "mass"});
}

TEST_F(BadInput, CsvLineWithThreeFields) {
  const std::string csv = dir_ + "/bed.csv";
  std::ofstream(csv) << "x,y,z,r\n1e-5,1e-5,1e-5,1e-5\n2e-5,2e-5,2e-5\n";
  expect_refused(run_app("bedstat", csv + " --json --domain 0,0,0,1e-4,1e-4,1e-4"),
                 {csv + ":3:", "3 fields"});
}

}  // namespace
