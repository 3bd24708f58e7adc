// packgen end to end (docs/physics.md §3, docs/architecture.md "Command-line programs"): --json keys, bad input
// exits 2 with one line, an unreachable --target-density still writes the bed (exit 0).
#include <gtest/gtest.h>

#include <string>

#include "run_command.hpp"

namespace {

using powderbed::test::run_app;
using powderbed::test::scratch_dir;

const std::string kSmall2D = "--dim 2 --domain 4e-6,4e-6 --psd mono:r=0.2e-6 --seed 3 ";

bool exists(const std::string& path) { return !powderbed::test::read_text(path).empty(); }

TEST(PackgenCli, JsonSummaryHasTheKeys) {
  const std::string dir = scratch_dir("packgen_json");
  const auto r = run_app("packgen", kSmall2D + "--approach 1 --json --out " + dir + "/bed.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"n\":", "\"density\":", "\"coordination\":", "\"coordination_by_tol\":",
                          "\"wall_time\":", "\"attempts\":", "\"target_reached\":true",
                          "\"collision\":\"grid\"", "\"approach\":1",
                          "\"size_sampling\":\"iid\""}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  }
  EXPECT_TRUE(exists(dir + "/bed.h5"));
}

TEST(PackgenCli, BadInputExitsTwoWithOneLine) {
  const std::string out = " --seed 1 --out " + scratch_dir("packgen_bad") + "/bed.h5";
  const std::string cases[] = {
      "--dim 2 --domain 4e-6,4e-6 --psd mono:r=-1e-7",                                // r <= 0
      "--dim 2 --domain 4e-6,4e-6 --psd gauss:mean=1e-6,sd=1e-7,min=2e-6,max=1e-6",  // min > max
      "--dim 2 --domain 4e-6,4e-6 --psd gauss:mean=1e-7,sd=1e-9,min=2e-6,max=3e-6",  // no mass
      "--dim 2 --domain 2e-6,2e-6 --psd mono:d=3e-6",                                 // too small
      "--dim 2 --domain 4e-6,4e-6 --psd mono:r=1e-7 --approach 3",                    // 3 in 2D
      "--dim 3 --domain 4e-6,4e-6 --psd mono:r=1e-7",                                 // dim
      "--dim 2 --domain 4e-6,4e-6 --psd mono:r=1e-7 --size-sampling sobol",           // sampling
  };
  for (const auto& args : cases) {
    const auto r = run_app("packgen", args + out);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
  }
  const auto small = run_app("packgen", cases[3] + out);
  EXPECT_NE(small.err.find("smaller than the smallest particle diameter 3e-06"), std::string::npos)
      << small.err;
}

TEST(PackgenCli, UnreachableTargetDensityWritesTheBedAndWarns) {
  const std::string dir = scratch_dir("packgen_target");
  const auto r = run_app("packgen", kSmall2D + "--approach 0 --target-density 0.95 " +
                                        "--max-failures 10 --tries 50 --json --out " + dir +
                                        "/bed.h5");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(exists(dir + "/bed.h5"));
  EXPECT_NE(r.err.find("not reached"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("\"target_reached\":false"), std::string::npos) << r.out;
}

}  // namespace
