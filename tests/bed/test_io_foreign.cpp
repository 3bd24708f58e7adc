// Foreign bed formats and decks (docs/decks.md): LAMMPS data files both ways, multi-snapshot and
// gzipped dumps, YADE text, GenGeo .geo, the printed-precision warning, the deck writer and its
// damping mapping. Each reader refuses a bad file with one line naming file and line.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>

#include "powderbed/bed/deck.hpp"
#include "powderbed/bed/deck_damping.hpp"
#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/input_file.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"

namespace powderbed::bed {
namespace {

namespace fs = std::filesystem;

class Foreign : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("powderbed_test_foreign_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
  }
  fs::path dir_;
};

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

// 27 particles on a cubic lattice with three materials, velocities that no short format prints
// exactly, periodic in x and z.
Bed three_material_bed() {
  Bed bed = simple_cubic_lattice(3, 1e-5);
  bed.domain.periodic = {true, false, true};
  for (std::size_t i = 0; i < bed.n(); ++i) {
    bed.material.push_back(static_cast<std::uint16_t>(i % 3));
    bed.vx.push_back(1.0 / 3.0 + static_cast<double>(i));
    bed.vy.push_back(-std::sqrt(2.0));
    bed.vz.push_back(1e-7 / 7.0);
  }
  return bed;
}

// --- LAMMPS data files ------------------------------------------------------------------------

TEST_F(Foreign, DataFileRoundTripKeepsTypesDensitiesVelocitiesAndPeriodicAxes) {
  const Bed bed = three_material_bed();
  LammpsDataOptions o;
  o.type_density = {4430, 7952, 8190};
  write_lammps_data(bed, path("bed.data"), o);
  const std::string text = slurp(path("bed.data"));
  EXPECT_NE(text.find("\n27 atoms\n3 atom types\n"), std::string::npos) << text.substr(0, 400);
  EXPECT_NE(text.find("# boundary p f p\n"), std::string::npos);
  EXPECT_NE(text.find("\n3 3 2.0000000000000002e-05 8190 "), std::string::npos) << "id 2: material 2";
  EXPECT_NE(text.find("\n1 1 2.0000000000000002e-05 4430 "), std::string::npos) << "id 0: material 0";
  EXPECT_NE(text.find("\nVelocities\n\n1 0.33333333333333331 -1.4142135623730951 "), std::string::npos);

  const Bed back = read_lammps_data(path("bed.data"));
  EXPECT_EQ(back.id, bed.id);
  EXPECT_EQ(back.radius, bed.radius);  // 2 r and 0.5 d are exact in binary
  EXPECT_EQ(back.x, bed.x);
  EXPECT_EQ(back.z, bed.z);
  EXPECT_EQ(back.vx, bed.vx);
  EXPECT_EQ(back.vz, bed.vz);
  EXPECT_EQ(back.material, bed.material);
  EXPECT_EQ(back.domain.periodic, bed.domain.periodic);
  EXPECT_EQ(back.domain.upper, bed.domain.upper);
  EXPECT_GE(back.provenance.printed_digits, 17);
  EXPECT_EQ(printed_precision_warning(back, 1e-6), "");
}

TEST_F(Foreign, DataFileDensityCountMustMatchTheMaterials) {
  LammpsDataOptions o;
  o.type_density = {4430, 7952};
  expect_input_error([&] { write_lammps_data(three_material_bed(), path("bed.data"), o); },
                     {"2 densities for 3 atom types"});
}

// What LAMMPS's write_data writes for atom_style sphere (29 Sep 2021): a title with the
// timestep, %-1.16e numbers, image flags, 7-column velocities, no boundary comment.
constexpr const char* kWriteData =
    "LAMMPS data file via write_data, version 29 Sep 2021, timestep = 50, units = si\n\n"
    "2 atoms\n2 atom types\n\n"
    "0.0000000000000000e+00 1.0000000000000000e-04 xlo xhi\n"
    "0.0000000000000000e+00 1.0000000000000000e-04 ylo yhi\n"
    "0.0000000000000000e+00 2.0000000000000001e-04 zlo zhi\n\n"
    "Atoms # sphere\n\n"
    "2 2 2.0000000000000002e-05 4.4300000000000000e+03 6.0000000000000002e-05 "
    "2.0000000000000002e-05 1.5000000000000000e-05 0 0 0\n"
    "1 1 2.0000000000000002e-05 7.9520000000000009e+03 2.0000000000000002e-05 "
    "2.0000000000000002e-05 1.5000000000000000e-05 0 0 0\n\n"
    "Velocities\n\n"
    "1 1.0000000000000000e-02 0.0000000000000000e+00 0.0000000000000000e+00 0 0 0\n"
    "2 0.0000000000000000e+00 -2.0000000000000000e-02 0.0000000000000000e+00 0 0 0\n";

TEST_F(Foreign, ReadsLammpsWriteData) {
  write("w.data", kWriteData);
  const Bed b = read_bed_any(path("w.data"));
  ASSERT_EQ(b.n(), 2u);
  EXPECT_EQ(b.id, (std::vector<std::uint64_t>{1, 0}));
  EXPECT_EQ(b.material, (std::vector<std::uint16_t>{1, 0}));
  EXPECT_EQ(b.radius[0], 1.0000000000000001e-05);
  EXPECT_EQ(b.x[0], 6.0000000000000002e-05);
  EXPECT_EQ(b.vx, (std::vector<double>{0.0, 0.01}));  // matched by id, not by line
  EXPECT_EQ(b.vy, (std::vector<double>{-0.02, 0.0}));
  EXPECT_EQ(b.domain.periodic, (std::array<bool, 3>{false, false, false}));
  EXPECT_EQ(b.domain.upper[2], 2.0000000000000001e-04);
}

TEST_F(Foreign, DataFileRefusals) {
  std::string truncated = kWriteData;
  truncated = truncated.substr(0, truncated.find("1 1 2.0000000000000002e-05"));
  write("t.data", truncated);
  expect_input_error([&] { read_lammps_data(path("t.data")); }, {path("t.data"), "1 of the 2 atoms"});
  std::string atomic = kWriteData;
  atomic.replace(atomic.find("# sphere"), 8, "# atomic");
  write("a.data", atomic);
  expect_input_error([&] { read_lammps_data(path("a.data")); }, {"Atoms # atomic", "sphere"});
  std::string stranger = kWriteData;
  stranger.replace(stranger.find("\n2 0.0000000000000000e+00 -2"), 3, "\n9 ");
  write("s.data", stranger);
  expect_input_error([&] { read_lammps_data(path("s.data")); }, {"Velocities of atom 9"});
  write("tri.data", "title\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n0 0 0 xy xz yz\n");
  expect_input_error([&] { read_lammps_data(path("tri.data")); }, {"tri.data:7:", "triclinic"});
}

// --- dumps ---------------------------------------------------------------------------------------

// Two snapshots as LAMMPS writes them with dump_modify time yes (ITEM: TIME before TIMESTEP)
// and a type column; the second at the default %g precision.
constexpr const char* kTwoSnapshots =
    "ITEM: TIME\n0\nITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\n"
    "ITEM: BOX BOUNDS pp ff pp\n0 1e-3\n0 1e-3\n0 1e-3\n"
    "ITEM: ATOMS id type x y z vx vy vz radius\n"
    "1 1 2.0000000000000002e-04 2e-4 2e-4 0 0 -0.5 1.0000000000000001e-05\n"
    "2 2 6.0000000000000005e-04 2e-4 2e-4 0 0 -0.5 2.0000000000000002e-05\n"
    "ITEM: TIME\n2.5e-07\nITEM: TIMESTEP\n250\nITEM: NUMBER OF ATOMS\n2\n"
    "ITEM: BOX BOUNDS pp ff pp\n0 1e-3\n0 1e-3\n0 1e-3\n"
    "ITEM: ATOMS id type x y z vx vy vz radius\n"
    "1 1 0.000200001 0.0002 0.000199999 0 0 -0.5 1e-05\n"
    "2 2 0.000600001 0.0002 0.000199999 0 0 -0.5 2e-05\n";

TEST_F(Foreign, DumpSnapshotsInOrderWithTimesTypesAndPrecision) {
  write("two.lammpstrj", kTwoSnapshots);
  const auto all = read_lammps_dump_all(path("two.lammpstrj"));
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].step, 0u);
  EXPECT_EQ(all[1].step, 250u);
  EXPECT_EQ(all[1].time, 2.5e-7);
  EXPECT_EQ(all[0].bed.material, (std::vector<std::uint16_t>{0, 1}));  // type - 1
  EXPECT_EQ(all[0].bed.domain.periodic, (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(all[0].bed.provenance.printed_digits, 17);
  EXPECT_EQ(all[1].bed.provenance.printed_digits, 6);
  // read_bed_any: the last snapshot.
  const Bed last = read_bed_any(path("two.lammpstrj"));
  EXPECT_EQ(last.x[0], 0.000200001);
  // 6 digits: centres off by up to 5e-10 m, gaps by ~2e-9 m, against 1e-6 x 3e-5 m of the
  // smallest pair: warned; against a tolerance of 0.1 (3e-6 m): not.
  const std::string warning = printed_precision_warning(last, 1e-6);
  EXPECT_NE(warning.find("6 significant digits"), std::string::npos) << warning;
  EXPECT_EQ(printed_precision_warning(last, 0.1), "");
  EXPECT_EQ(printed_precision_warning(all[0].bed, 1e-6), "") << "17 digits: exact";
}

TEST_F(Foreign, GzippedDumpReadsAsThePlainOne) {
  write("two.dump", kTwoSnapshots);
  const std::string gzip = "gzip -k -n '" + path("two.dump") + "'";
  if (std::system("command -v gzip > /dev/null 2>&1") != 0) GTEST_SKIP() << "gzip not on PATH";
  ASSERT_EQ(std::system(gzip.c_str()), 0);
  const Bed plain = read_bed_any(path("two.dump"));
  const Bed zipped = read_bed_any(path("two.dump.gz"));
  EXPECT_EQ(zipped.x, plain.x);
  EXPECT_EQ(zipped.id, plain.id);
  EXPECT_EQ(read_lammps_dump_all(path("two.dump.gz")).size(), 2u);
  // A truncated .gz is refused, not read as the part that survived.
  std::string bytes = slurp(path("two.dump.gz"));
  write("cut.dump.gz", bytes.substr(0, bytes.size() / 2));
  expect_input_error([&] { read_bed_any(path("cut.dump.gz")); }, {"cut.dump.gz", "damaged gzip"});
}

// A gzip stream is inflated only up to the readers' memory guard (issue 36: a 3 MB .gz that
// inflated to 3 GB ended in bad_alloc): 8 MB of zeros (about 8 KB gzipped) against a 1 MB guard
// is refused naming the file and the guard, and read whole under a guard above its size.
TEST_F(Foreign, GunzipStopsAtTheMemoryGuard) {
  if (std::system("command -v gzip > /dev/null 2>&1") != 0) GTEST_SKIP() << "gzip not on PATH";
  const std::string cmd = "head -c 8000000 /dev/zero | gzip -c > '" + path("zeros.dump.gz") + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_LT(fs::file_size(path("zeros.dump.gz")), 100000u);
  expect_input_error([&] { detail::read_text(path("zeros.dump.gz"), 1e6); },
                     {"zeros.dump.gz", "more than 1000000 bytes once gunzipped", "memory guard"});
  EXPECT_EQ(detail::read_text(path("zeros.dump.gz"), 1e7), std::string(8000000, '\0'));
  // The guard of the readers themselves is a quarter of the memory this process may use.
  EXPECT_GT(detail::text_guard_bytes(), 0.0);
  EXPECT_LE(detail::text_guard_bytes(), 0.25 * detail::usable_memory_bytes());
}

// The stored size is held against the same guard before anything is read.
TEST_F(Foreign, ATextFileAboveTheGuardIsRefusedBeforeReading) {
  write("big.csv", std::string(2000, 'x'));
  expect_input_error([&] { detail::read_text(path("big.csv"), 1000); },
                     {"big.csv", "2000 bytes", "too large"});
}

// Every reader refuses a FIFO (its open would block until a writer came) and a character device
// (/dev/zero never ends) before opening it, naming the path and what it is (issue 36).
TEST_F(Foreign, EveryReaderRefusesWhatIsNotARegularFile) {
  for (const char* name : {"p.h5", "p.csv", "p.dump", "p.data", "p.txt", "p.geo", "p.dump.gz"})
    ASSERT_EQ(::mkfifo(path(name).c_str(), 0600), 0) << name;
  Domain box;
  box.upper = {1e-4, 1e-4, 1e-4};
  expect_input_error([&] { read_bed_h5(path("p.h5")); }, {"p.h5", "FIFO", "regular file"});
  expect_input_error([&] { read_bed_csv(path("p.csv"), box); }, {"p.csv", "FIFO"});
  expect_input_error([&] { read_lammps_dump(path("p.dump")); }, {"p.dump", "FIFO"});
  expect_input_error([&] { read_lammps_dump_all(path("p.dump.gz")); }, {"p.dump.gz", "FIFO"});
  expect_input_error([&] { read_lammps_data(path("p.data")); }, {"p.data", "FIFO"});
  expect_input_error([&] { read_yade_text(path("p.txt")); }, {"p.txt", "FIFO"});
  expect_input_error([&] { read_gengeo(path("p.geo")); }, {"p.geo", "FIFO"});
  for (const char* name : {"p.h5", "p.csv", "p.dump", "p.data"})
    expect_input_error([&] { read_bed_any(path(name), &box); }, {name, "FIFO"});
  fs::create_symlink("/dev/zero", path("zero.csv"));
  expect_input_error([&] { read_bed_csv(path("zero.csv"), box); }, {"zero.csv", "character device"});
  expect_input_error([&] { read_bed_h5("/dev/null"); }, {"/dev/null", "character device"});
  expect_input_error([&] { require_regular_file(dir_.string(), "--in"); }, {"--in", "folder"});
  EXPECT_NO_THROW(require_regular_file(path("missing.h5"), "--in"));  // the open names it
}

// Messages quote what they read in one printable line: control bytes and the bytes of a binary
// file as \xNN, printable UTF-8 kept, long text cut.
TEST(QuotedExcerpt, OneLineOfPrintableText) {
  EXPECT_EQ(quoted_excerpt("abc"), "'abc'");
  EXPECT_EQ(quoted_excerpt(std::string("a\nb\r\0\x7f\xff", 7)), "'a\\x0ab\\x0d\\x00\\x7f\\xff'");
  EXPECT_EQ(quoted_excerpt("5 \xc2\xb5m"), "'5 \xc2\xb5m'");  // µ
  EXPECT_EQ(quoted_excerpt("\xc2\x85"), "'\\xc2\\x85'");      // C1 control U+0085
  EXPECT_EQ(quoted_excerpt(std::string(100, 'x'), 10), "'xxxxxxxxxx...'");
}

// A LAMMPS data file's density column must be a mass density, even though the bed keeps none.
TEST_F(Foreign, DataFileRefusesADensityThatIsNotPositive) {
  for (const char* density : {"nan", "-7952", "0", "inf"}) {
    write("d.data", std::string("t\n\n1 atoms\n1 atom types\n0 4e-5 xlo xhi\n0 4e-5 ylo yhi\n"
                                "0 4e-5 zlo zhi\n\nAtoms # sphere\n\n1 1 2e-5 ") +
                        density + " 2e-5 2e-5 2e-5\n");
    expect_input_error([&] { read_lammps_data(path("d.data")); }, {"d.data:11", "density", density});
  }
}

TEST_F(Foreign, DumpRefusesATypeOfZero) {
  std::string dump = kTwoSnapshots;
  dump.replace(dump.find("\n2 2 6.0000000000000005e-04"), 4, "\n2 0");
  write("bad.dump", dump);
  expect_input_error([&] { read_lammps_dump_all(path("bad.dump")); }, {"bad.dump:13:", "type is '0'"});
}

// --- YADE and GenGeo -----------------------------------------------------------------------------

TEST_F(Foreign, YadeTextWithItsBoundingBoxOrAGivenDomain) {
  write("s.txt", "#format x_y_z_r\n1e-4 1e-4 1e-4 2e-5\n2e-4 1e-4 1e-4 3e-5\n");
  const Bed b = read_bed_any(path("s.txt"));
  ASSERT_EQ(b.n(), 2u);
  EXPECT_EQ(b.id, (std::vector<std::uint64_t>{0, 1}));
  EXPECT_EQ(b.domain.lower, (std::array<double, 3>{1e-4 - 2e-5, 1e-4 - 3e-5, 1e-4 - 3e-5}));
  EXPECT_EQ(b.domain.upper[0], 2e-4 + 3e-5);
  Domain box;
  box.upper = {1e-3, 1e-3, 1e-3};
  EXPECT_EQ(read_bed_any(path("s.txt"), &box).domain.upper, box.upper);
  write("bad.txt", "#format x_y_z_r\n1e-4 1e-4 1e-4\n");
  expect_input_error([&] { read_bed_any(path("bad.txt")); }, {"bad.txt:2:", "3 columns", "x y z r"});
  write("ext.txt", "#format x_y_z_r_attrs\n1e-4 1e-4 1e-4 2e-5 7\n");
  expect_input_error([&] { read_bed_any(path("ext.txt")); }, {"ext.txt:2:", "5 columns"});
}

constexpr const char* kGeo =
    "LSMGeometry 1.2\n"
    "BoundingBox 0 0 0 1e-3 1e-3 5e-4\n"
    "PeriodicBoundaries 1 0 0\n"
    "Dimension 3D\n"
    "BeginParticles\nSimple\n3\n"
    "1e-4 1e-4 1e-4 5e-5 0 0\n"
    "3e-4 1e-4 1e-4 5e-5 1 2\n"
    "5e-4 1e-4 1e-4 4e-5 7 0\n"
    "EndParticles\nBeginConnect\n1\n0 1 0\nEndConnect\n";

TEST_F(Foreign, GenGeoGeometryFile) {
  write("g.geo", kGeo);
  const Bed b = read_bed_any(path("g.geo"));
  ASSERT_EQ(b.n(), 3u);
  EXPECT_EQ(b.id, (std::vector<std::uint64_t>{0, 1, 7}));
  EXPECT_EQ(b.radius[2], 4e-5);
  EXPECT_EQ(b.domain.upper, (std::array<double, 3>{1e-3, 1e-3, 5e-4}));
  EXPECT_EQ(b.domain.periodic, (std::array<bool, 3>{true, false, false}));
  std::string bad = kGeo;
  bad.replace(bad.find("3e-4 1e-4 1e-4 5e-5 1 2"), 23, "3e-4 1e-4 1e-4 5e-5 1");
  write("bad.geo", bad);
  expect_input_error([&] { read_bed_any(path("bad.geo")); }, {"bad.geo:9:", "x y z r id tag"});
  write("old.geo", "LSMGeometry 0.9\n");
  expect_input_error([&] { read_bed_any(path("old.geo")); }, {"old.geo:1:", "LSMGeometry 1.2"});
}

// --- decks -----------------------------------------------------------------------------------------

TEST(DeckDamping, TsujiInputSolvesTheAlphaOfOurDashpot) {
  // Hertz: alpha(e) = zeta sqrt(6); linear: 2 zeta (deck_damping.hpp).
  for (double zeta : {0.01, 0.1, 0.3, 0.5}) {
    EXPECT_NEAR(tsuji_alpha(lammps_tsuji_input(zeta, true, "z")), zeta * std::sqrt(6.0), 1e-12);
    EXPECT_NEAR(tsuji_alpha(lammps_tsuji_input(zeta, false, "z")), 2 * zeta, 1e-12);
  }
  // The value measured by hand against LAMMPS 29 Sep 2021 (docs/results/deck-damping.md).
  EXPECT_NEAR(lammps_tsuji_input(0.1, true, "z"), 0.61040, 1e-5);
  expect_input_error([] { lammps_tsuji_input(0.6, true, "material.damping"); },
                     {"material.damping", "0.6", "0.5196"});
}

TEST(DeckDamping, LiggghtsRestitutionOfTheBenchDeck) {
  // zeta = 0.1: b = 0.1 / sqrt(5/6) = 0.109545, e = exp(-pi b / sqrt(1 - b^2)) = 0.707351 (by
  // hand; the deck with it gives deposit's restitution to 1e-15, docs/results/deck-damping.md).
  EXPECT_NEAR(liggghts_hertz_restitution(0.1, "z"), 0.707351, 1e-6);
  EXPECT_EQ(liggghts_hertz_restitution(0.0, "z"), 1.0);
  expect_input_error([] { liggghts_hertz_restitution(0.95, "material.damping"); },
                     {"material.damping", "0.9129"});
}

DeckLaws hertz_laws() {
  DeckLaws laws;
  laws.young = 193e9;
  laws.poisson = 0.26;
  laws.wall_young = 193e9;
  laws.wall_poisson = 0.26;
  laws.damping_ratio = 0.1;
  laws.friction = 0.1;
  laws.gravity = 9.81;
  laws.viscosity = 2.1e-5;
  laws.dt = 1e-9;
  laws.density = {4430, 7952, 8190};
  laws.origin = {"a test"};
  return laws;
}

TEST_F(Foreign, DeckFilesCarryTheLawsAndTheDomain) {
  const Bed bed = three_material_bed();
  write_deck(bed, hertz_laws(), DeckEngine::lammps, path("bed.data"));
  const std::string lmp = slurp(path("in.bed.lammps"));
  EXPECT_NE(lmp.find("boundary       p f p\n"), std::string::npos);
  EXPECT_NE(lmp.find("read_data      bed.data\n"), std::string::npos);
  // 4/3 E* with E* = E / (2 (1 - nu^2)) = 1.03496e11 Pa for two 316L spheres.
  EXPECT_NE(lmp.find("pair_coeff     * * hertz 137995137995."), std::string::npos) << lmp;
  EXPECT_NE(lmp.find("damping tsuji"), std::string::npos);
  EXPECT_NE(lmp.find("yplane 0 "), std::string::npos) << "walls on the one fixed axis";
  EXPECT_EQ(lmp.find("xplane"), std::string::npos) << "no wall on a periodic axis";
  EXPECT_NE(lmp.find("dump_modify    snapshots sort id format float %.17g"), std::string::npos);
  EXPECT_NE(lmp.find("#   a test\n"), std::string::npos);
  EXPECT_NE(slurp(path("bed.data")).find("\n4 atom types\n"), std::string::npos) << "3 + walls";

  write_deck(bed, hertz_laws(), DeckEngine::liggghts, path("bed.data"));
  const std::string lig = slurp(path("in.bed.liggghts"));
  EXPECT_NE(lig.find("coefficientRestitution peratomtypepair 4 0.70735"), std::string::npos) << lig;
  EXPECT_NE(lig.find("primitive type 4 yplane"), std::string::npos);

  // The linear law: LIGGGHTS takes a wall's model settings after its plane, and its dashpot for
  // m* = m against a wall, sqrt(2) times the pair's m* = m/2 (one material here: equal masses).
  DeckLaws linear = hertz_laws();
  linear.law = "linear";
  linear.stiffness = 1e3;
  linear.density = {7952};
  write_deck(simple_cubic_lattice(2, 1e-5), linear, DeckEngine::liggghts, path("lin.data"));
  const std::string lin = slurp(path("in.lin.liggghts"));
  EXPECT_NE(lin.find("primitive type 2 zplane 0 absolute_damping on\n"), std::string::npos) << lin;
  const double mass = 7952 * 4.0 / 3.0 * 3.141592653589793 * 1e-15;  // r = 1e-5 m
  const auto at = lin.find("gamman_abs peratomtypepair 2 ");
  ASSERT_NE(at, std::string::npos) << lin;
  std::istringstream row(lin.substr(at + 29, lin.find('\n', at) - at - 29));
  double g[4] = {};
  row >> g[0] >> g[1] >> g[2] >> g[3];
  // Rows: particle-particle, particle-wall; wall-particle, wall-wall (unused).
  EXPECT_NEAR(g[0], 2 * 0.1 * std::sqrt(0.5 * mass * 1e3), 1e-12 * g[0]);
  EXPECT_NEAR(g[1], 2 * 0.1 * std::sqrt(mass * 1e3), 1e-12 * g[1]);
  EXPECT_EQ(g[2], g[1]);

  DeckLaws too_damped = hertz_laws();
  too_damped.damping_ratio = 0.7;
  expect_input_error([&] { write_deck(bed, too_damped, DeckEngine::lammps, path("x.data")); },
                     {"material.damping", "0.7"});
  EXPECT_FALSE(fs::exists(path("x.data"))) << "nothing written";
  EXPECT_FALSE(fs::exists(path("in.x.lammps")));
}

}  // namespace
}  // namespace powderbed::bed
