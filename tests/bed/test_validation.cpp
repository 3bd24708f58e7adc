// The shared bed validation and the temporary-file registry (docs/hardening.md), below the
// end-to-end table of tests/apps/test_hardening.cpp: where exactly the geometry check draws its
// lines, and what the registry removes and what it leaves alone.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"
#include "powderbed/bed/temp_files.hpp"

namespace {

namespace fs = std::filesystem;
using powderbed::InputError;
using powderbed::bed::Bed;

Bed one_sphere(double x, double r) {
  Bed b;
  b.domain.upper = {1e-4, 1e-4, 1e-4};
  b.add(x, 5e-5, 5e-5, r);
  return b;
}

TEST(ValidateGeometry, SpheresTouchingOrCrossingAWallAreAccepted) {
  EXPECT_NO_THROW(one_sphere(1e-5, 1e-5).validate_geometry("t"));      // touching x = 0
  EXPECT_NO_THROW(one_sphere(0.0, 1e-5).validate_geometry("t"));       // centre on the wall
  EXPECT_NO_THROW(one_sphere(-1e-5, 1e-5).validate_geometry("t"));     // a radius outside: still touches
  EXPECT_NO_THROW(powderbed::bed::simple_cubic_lattice(3, 1e-5).validate_geometry("t"));
}

TEST(ValidateGeometry, ACentreMoreThanItsRadiusOutsideIsRefusedNamingIt) {
  try {
    one_sphere(-1.0001e-5 - 1e-9, 1e-5).validate_geometry("bed.h5");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bed.h5"), std::string::npos) << what;
    EXPECT_NE(what.find("particle 0"), std::string::npos) << what;
    EXPECT_NE(what.find("outside the domain"), std::string::npos) << what;
  }
  EXPECT_THROW(one_sphere(1.0, 1e-5).validate_geometry("t"), InputError);  // (1, ., .) m in 100 um
}

TEST(ValidateGeometry, ARadiusAsLargeAsTheSmallestExtentIsTheUnitSlip) {
  Bed b = one_sphere(5e-5, 5e-5);
  b.domain.upper[2] = 1e-3;  // smallest extent 1e-4 (x and y)
  EXPECT_NO_THROW(b.validate_geometry("t"));  // r = half the extent: one sphere fills the box
  b.radius[0] = 1e-4;
  try {
    b.validate_geometry("t");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("um"), std::string::npos) << e.what();
  }
}

TEST(ValidateGeometry, TwoDimensionalBedsIgnoreZ) {
  Bed b;
  b.domain.dimension = 2;
  b.domain.upper = {1e-4, 1e-4, 0};
  b.add(5e-5, 5e-5, 0, 1e-5);
  EXPECT_NO_THROW(b.validate_geometry("t"));
}

TEST(TempFiles, NamesCarryThePid) {
  EXPECT_EQ(powderbed::bed::temp_path_for("a/b.h5"), "a/b.h5.tmp." + std::to_string(::getpid()));
}

TEST(TempFiles, RegisteredTemporariesAreRemovedAndUnregisteredOnesKept) {
  const std::string dir = "/tmp/powderbed_test_" + std::to_string(::getpid()) + "_temps";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string a = dir + "/a.tmp", b = dir + "/b.tmp";
  std::ofstream(a) << "a";
  std::ofstream(b) << "b";
  powderbed::bed::register_temp_file(a);
  powderbed::bed::register_temp_file(b);
  powderbed::bed::unregister_temp_file(b);
  powderbed::bed::remove_temp_files();
  EXPECT_FALSE(fs::exists(a));
  EXPECT_TRUE(fs::exists(b));
  powderbed::bed::unregister_temp_file(a);
  {
    powderbed::bed::TempFile t(dir + "/c.tmp");
    std::ofstream(t.path()) << "c";
  }
  EXPECT_FALSE(fs::exists(dir + "/c.tmp"));  // removed when not released
  fs::remove_all(dir);
}

TEST(TempFiles, StaleTemporariesOfDeadProcessesGoLiveOnesStay) {
  const std::string dir = "/tmp/powderbed_test_" + std::to_string(::getpid()) + "_stale";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string out = dir + "/out.h5";
  // A pid that has surely exited: a child we waited for.
  const pid_t child = ::fork();
  if (child == 0) std::_Exit(0);
  ::waitpid(child, nullptr, 0);
  const std::string dead = out + ".tmp." + std::to_string(child);
  const std::string live = out + ".tmp." + std::to_string(::getppid());  // our parent is alive
  const std::string other = out + ".tmp.notapid";
  for (const auto& f : {dead, live, other}) std::ofstream(f) << "x";
  EXPECT_EQ(powderbed::bed::remove_stale_temp_files(out), 1);
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(other));
  fs::remove_all(dir);
}

TEST(TempFiles, AFailedWriteLeavesTheOldFileAndNoTemporary) {
  const std::string dir = "/tmp/powderbed_test_" + std::to_string(::getpid()) + "_atomic";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string out = dir + "/bed.csv";
  std::ofstream(out) << "old";
  Bed bad = powderbed::bed::simple_cubic_lattice(2, 1e-5);
  bad.radius[0] = -1;  // the writer refuses it
  EXPECT_THROW(powderbed::bed::write_bed_csv(bad, out), InputError);
  std::ifstream in(out);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "old");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1);
  fs::remove_all(dir);
}

}  // namespace
