// The paper's validation scene end to end (issue 5, SPEC.md §5): sinter with
// data/scenes/gz2016-sinter.ini on the deposit scene's bed (tests/data/gz2016-deposit.h5), the
// full 201 x 101 x 61 grid and the whole track, on one thread (CI runs two tests at a time):
// about 20–30 s.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

#include "run_command.hpp"

using powderbed::test::json_number;

namespace {

TEST(SinterPaper, MeltPoolAndEnergyBalanceOnThePapersScene) {
  const std::string src = POWDERBED_SOURCE_DIR;
  const std::string out = "/tmp/powderbed_sinter_paper_" + std::to_string(::getpid()) + ".h5";
  const auto r = powderbed::test::run_app(
      "sinter", "--config " + src + "/data/scenes/gz2016-sinter.ini --bed " + src +
                    "/tests/data/gz2016-deposit.h5 --out " + out + " --json --threads 1");
  ASSERT_EQ(r.status, 0) << r.err;
  // The bar: absorbed laser = internal energy change + boundary and surface losses
  // within 0.5 %; the solver books every joule, so anything above round-off is a bug.
  EXPECT_LT(json_number(r.out, "energy_balance_error"), 5e-3);
  // Melt pool against [GZ] (model 30 / 85 / 20 um, experiment 26 / 75 / 30 um). Width and
  // height are set by which 27 um particles melt, so they are quantised by about a particle
  // radius: bands of about +-15 um around the paper's model hold for any bed of this PSD.
  const double height = json_number(r.out, "height") * 1e6;
  const double width = json_number(r.out, "width") * 1e6;
  const double depth = json_number(r.out, "depth") * 1e6;
  EXPECT_GT(width, 70.0);
  EXPECT_LT(width, 100.0);
  EXPECT_GT(height, 20.0);
  EXPECT_LT(height, 45.0);
  // With exp(-beta H_layer) on the substrate it just melts (docs/results/sinter-gz2016.md
  // explains the gap to the paper's 20 um); it must melt, and not deeper than the experiment.
  EXPECT_GT(depth, 0.0);
  EXPECT_LT(depth, 30.0);
  EXPECT_GT(json_number(r.out, "particles_molten"), 50.0);
  std::remove(out.c_str());
  std::remove((out.substr(0, out.size() - 3) + ".xmf").c_str());
}

}  // namespace
