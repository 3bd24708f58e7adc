// deposit --export-deck (docs/decks.md): the settled bed as a LAMMPS data file and an input deck
// with the run's laws and time step beside --out; an engine or a scene a deck cannot take exits 2
// before the run, writing nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

// Two 20 um particles resting 1 um above the floor of a 0.3 mm box, periodic in y.
std::string resting_pair(const std::string& dir) {
  bed::Bed b;
  b.domain.upper = {0.3e-3, 0.3e-3, 0.3e-3};
  b.domain.periodic = {false, true, false};
  b.add(1e-4, 1.5e-4, 21e-6, 20e-6);
  b.add(2e-4, 1.5e-4, 21e-6, 20e-6);
  const std::string path = dir + "/in.h5";
  bed::write_bed_h5(b, path);
  return path;
}

TEST(DepositDeck, WritesTheRunsDeckBesideTheBed) {
  const std::string dir = test::scratch_dir("deposit_deck");
  const auto r = test::run_app("deposit", "--in " + resting_pair(dir) + " --t-end 1e-6 --dt 1e-9 "
                               "--material.density 8190 --seed 1 --out " + dir + "/bed.h5 "
                               "--export-deck liggghts");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string deck = test::read_text(dir + "/in.bed.liggghts");
  EXPECT_NE(deck.find("timestep       1.0000000000000001e-09"), std::string::npos) << deck;
  EXPECT_NE(deck.find("boundary       f p f"), std::string::npos);
  EXPECT_NE(deck.find("the deposit run that wrote " + dir + "/bed.h5"), std::string::npos);
  // The bed as settled, with the run's velocities and density.
  const bed::Bed data = bed::read_lammps_data(dir + "/bed.data");
  const bed::Bed settled = bed::read_bed_h5(dir + "/bed.h5");
  EXPECT_EQ(data.z, settled.z);
  EXPECT_EQ(data.vz, settled.vz);
  EXPECT_EQ(data.domain.periodic, settled.domain.periodic);
  EXPECT_NE(test::read_text(dir + "/bed.data").find(" 8190 "), std::string::npos);
}

TEST(DepositDeck, AnEngineOrZetaItCannotTakeExits2BeforeTheRun) {
  const std::string dir = test::scratch_dir("deposit_deck_bad");
  const std::string in = resting_pair(dir);
  auto r = test::run_app("deposit", "--in " + in + " --t-end 1e-6 --seed 1 --out " + dir +
                                        "/bed.h5 --export-deck yade");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--export-deck: 'yade'"), std::string::npos) << r.err;
  // LAMMPS's tsuji damping reaches zeta 0.5196 at most (docs/decks.md).
  r = test::run_app("deposit", "--in " + in + " --t-end 1e-6 --seed 1 --material.damping 0.8 "
                               "--out " + dir + "/bed.h5 --export-deck lammps");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("zeta 0.8"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bed.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/bed.data"));
}

}  // namespace
