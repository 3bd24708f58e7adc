// End-to-end tests of build (docs/build.md): bad input exits 2 with one line before any layer is
// spread; a build stopped after layer 2 and continued with --in equals the uninterrupted one bit
// for bit; the per-layer files and the report.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <tuple>
#include <vector>
#include <fstream>
#include <string>
#include <utility>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/thermal/part_porosity.hpp"
#include "run_command.hpp"

using namespace powderbed;

namespace {

// The small build (tests/data/build-small/): 120 spheres of 30 um spread by a blade over a
// 1.5 x 0.3 mm strip, two tracks of 100 W at 1 m/s (Beer-Lambert, 20 um grid) behind the supply.
const std::string kScenes = std::string(POWDERBED_TEST_DATA) + "/build-small";
const std::string kConfig = kScenes + "/build.ini";

}  // namespace

TEST(BuildCli, BadInputExits2WithOneLineAndWritesNothing) {
  const std::string dir = test::scratch_dir("build_bad");
  const std::string config = kConfig;
  std::ofstream(dir + "/off.csv") << "x0,y0,x1,y1,power,speed\n0.5e-3,0.1e-3,2.5e-3,0.1e-3,100,1\n";
  std::ofstream(dir + "/drop.ini") << "psd = mono:d=30e-6\ndomain = 1e-3,1e-3,1e-3\ncount = 10\n";
  std::filesystem::create_directories(dir + "/full");
  std::ofstream(dir + "/full/keep.txt") << "a user's file\n";
  const std::string out = " --out " + dir + "/run";
  const std::pair<std::string, std::string> cases[] = {
      {"--layers 0" + out, "--layers"},
      // The box (0.6 mm, gap 60 um, 30 um layers) holds 18 layers; a count that would wrap
      // past the last layer number is refused the same way.
      {"--layers 19" + out, "--layers"},
      {"--layers 18446744073709551615" + out, "--layers"},
      {"--sinter-args '--scan.hatch 0'" + out, "scan.hatch"},
      {"--sinter-args '--scan.hatch -1e-6'" + out, "scan.hatch"},
      {"--sinter " + kScenes + "/scan-track.ini --sinter-args '--scan-path " + dir + "/off.csv'" + out,
       "scan"},
      {"--spread " + dir + "/drop.ini" + out, "--spread"},
      {"--spread-args '--recoater.gap 0'" + out, "recoater.gap"},
      {"--spread-args '--supply.count 0 --supply.dosing 0'" + out, "supply.dosing"},
      {"--spread-args '--supply.count 0 --supply.dosing -2'" + out, "supply.dosing"},
      // 30 um spheres under 20 um layers: thinner than the finest particle (one layer is fine).
      {"--layers 2 --spread-args '--recoater.layer-thickness 20e-6'" + out, "recoater.layer-thickness"},
      {"--out " + dir + "/full", "--out"},
      {"--out ''", "--out: empty"},
      {"--out " + dir + "/" + std::string(300, 'a'), "characters long"},
      {"--out /proc/run", "--out"},  // a file system that makes no folders
      {"--spread-args '--in " + dir + "/x.h5'" + out, "'--in' is set by the build itself"},
      {"--sinter-args '--bed x.h5 --out y.h5'" + out, "'--bed' is set by the build itself"},
      {"--sinter-args '--fuse.melt-fraction=0.3'" + out, "'--fuse.melt-fraction' is set by the build"},
      {"--in " + dir + "/missing.h5" + out, "--in"},
  };
  for (const auto& [args, field] : cases) {
    const auto r = test::run_app("build", "--config " + config + " " + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(field), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/run")) << args;
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/full/keep.txt"));
}

TEST(BuildCli, ContinuedBuildEqualsTheUninterruptedOneBitForBit) {
  const std::string dir = test::scratch_dir("build_restart");
  const std::string config = kConfig;
  const auto whole = test::run_app("build", "--config " + config + " --layers 3 --threads 2 --json --out " + dir + "/whole");
  ASSERT_EQ(whole.status, 0) << whole.err;
  // An empty folder with a dead process's temporary in it is taken; "first/" names the folder.
  std::filesystem::create_directories(dir + "/first");
  std::ofstream(dir + "/first/layer-001.h5.tmp.999999999") << "left by a killed build\n";
  const auto first = test::run_app("build", "--config " + config + " --layers 2 --threads 1 --out " + dir + "/first/");
  ASSERT_EQ(first.status, 0) << first.err;
  const auto rest = test::run_app("build", "--config " + config + " --layers 1 --in " + dir +
                                               "/first/layer-002.h5 --out " + dir + "/rest");
  ASSERT_EQ(rest.status, 0) << rest.err;
  // Every layer's files, and the report's layers.
  for (const char* f : {"layer-001.h5", "layer-001-spread.h5", "layer-001-scan.h5",
                        "layer-001-scan.xmf", "layer-003.h5", "build.json"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/whole/" + f)) << f;
  EXPECT_NE(whole.out.find("\"lack_of_fusion\""), std::string::npos) << whole.out;
  EXPECT_NE(whole.out.find("\"layer\":3"), std::string::npos) << whole.out;
  const std::string a = dir + "/whole/layer-003.h5", b = dir + "/rest/layer-003.h5";
  const bed::Bed ba = bed::read_bed_h5(a), bb = bed::read_bed_h5(b);
  ASSERT_EQ(ba.n(), bb.n());
  ASSERT_GT(ba.n(), 0u);
  EXPECT_EQ(ba.x, bb.x);
  EXPECT_EQ(ba.y, bb.y);
  EXPECT_EQ(ba.z, bb.z);
  EXPECT_EQ(ba.vz, bb.vz);
  EXPECT_EQ(ba.id, bb.id);
  const dem::SpreadState sa = dem::read_spread_state(a, ba), sb = dem::read_spread_state(b, bb);
  EXPECT_EQ(sa.layers_done, 3u);
  EXPECT_EQ(sa.step, sb.step);
  EXPECT_FALSE(sa.floor.empty());
  EXPECT_EQ(sa.floor.z, sb.floor.z);
  EXPECT_EQ(sa.pair_history, sb.pair_history);
  EXPECT_EQ(sa.wall_history, sb.wall_history);
  // The part's record (part_porosity.hpp) goes on from the layer file too.
  const thermal::PartRecord pa = thermal::read_part_record(a), pb = thermal::read_part_record(b);
  EXPECT_EQ(pa.layers, 3u);
  EXPECT_EQ(pa.top, pb.top);
  EXPECT_EQ(pa.below_last, pb.below_last);
  EXPECT_NE(pa.below_last, pa.top);  // layer 3 raised the top over what layer 2 left
  EXPECT_EQ(pa.scanned, pb.scanned);
  ASSERT_EQ(pa.never_molten.size(), pb.never_molten.size());
  for (std::size_t c = 0; c < pa.never_molten.size(); ++c) {
    ASSERT_EQ(pa.never_molten[c].size(), pb.never_molten[c].size()) << c;
    for (std::size_t k = 0; k < pa.never_molten[c].size(); ++k) {
      EXPECT_EQ(pa.never_molten[c][k].lo, pb.never_molten[c][k].lo);
      EXPECT_EQ(pa.never_molten[c][k].hi, pb.never_molten[c][k].hi);
    }
  }
  EXPECT_NE(whole.out.find("\"part_porosity\""), std::string::npos) << whole.out;
}

namespace {

// In-place damage of a copied layer file through the HDF5 C API (the writers refuse to write
// such files).
struct LayerFile {
  explicit LayerFile(const std::string& path) : f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)) {}
  ~LayerFile() { H5Fclose(f); }
  void restart_double(const char* name, double v) const {
    H5Adelete_by_name(f, "/restart", name, H5P_DEFAULT);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate_by_name(f, "/restart", name, H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                      H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
    H5Sclose(space);
  }
  // Particle 0's centre moved to (x, y, z).
  void move_first(double x, double y, double z) const {
    const hid_t set = H5Dopen2(f, "/particles/position", H5P_DEFAULT);
    const hid_t space = H5Dget_space(set);
    hsize_t dims[2];
    H5Sget_simple_extent_dims(space, dims, nullptr);
    std::vector<double> rows(dims[0] * dims[1]);
    H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows.data());
    rows[0] = x;
    rows[1] = y;
    rows[2] = z;
    H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows.data());
    H5Sclose(space);
    H5Dclose(set);
  }
  // /restart/pair_ids declaring 1e9 rows with none stored (a few bytes on disk).
  void huge_pair_ids() const {
    H5Ldelete(f, "/restart/pair_ids", H5P_DEFAULT);
    const hsize_t dims[2] = {1000000000, 2};
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    H5Dclose(H5Dcreate2(f, "/restart/pair_ids", H5T_STD_U64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                        H5P_DEFAULT));
    H5Sclose(space);
  }
  void no_restart() const { H5Ldelete(f, "/restart", H5P_DEFAULT); }
  hid_t f;
};

}  // namespace

// A layer file whose /restart or particles cannot be continued is refused by build --in and by
// deposit --in before anything runs or is written (issue 36's probe: a 1 s time step ran the
// spread to z = -2e39 m and wrote layer-002-spread.h5; 1e9 declared pair rows threw bad_alloc).
TEST(BuildCli, DamagedLayerFileIsRefusedBeforeAnyWork) {
  const std::string dir = test::scratch_dir("build_damaged_in");
  const auto one = test::run_app("build", "--config " + kConfig + " --layers 1 --out " + dir + "/one");
  ASSERT_EQ(one.status, 0) << one.err;
  const std::string layer = dir + "/one/layer-001.h5";
  const bed::Bed good = bed::read_bed_h5(layer);
  // Where layer 1's solid stands highest: a centre a tenth of a radius above the plate there is
  // inside it.
  const bed::HeightMap floor = dem::read_spread_state(layer, good).floor;
  const auto top = static_cast<std::size_t>(
      std::max_element(floor.z.begin(), floor.z.end()) - floor.z.begin());
  ASSERT_GT(floor.z[top], 0.5 * good.radius[0]);
  const double top_x = floor.x0 + floor.dx * static_cast<double>(top % floor.nx);
  const double top_y = floor.y0 + floor.dy * static_cast<double>(top / floor.nx);
  const std::vector<std::tuple<std::string, std::function<void(const LayerFile&)>, std::string>> cases = {
      {"dt_one_second", [](const LayerFile& l) { l.restart_double("dt", 1.0); }, "stable bound"},
      {"dt_nan", [](const LayerFile& l) { l.restart_double("dt", NAN); }, "dt is nan"},
      {"dt_zero", [](const LayerFile& l) { l.restart_double("dt", 0.0); }, "dt is 0"},
      {"inside_solid",
       [&](const LayerFile& l) { l.move_first(top_x, top_y, good.domain.lower[2] + 0.1 * good.radius[0]); },
       "inside the solid"},
      {"huge_pair_ids", [](const LayerFile& l) { l.huge_pair_ids(); }, "declares 1000000000 rows"},
      {"no_restart", [](const LayerFile& l) { l.no_restart(); }, "/restart"},
  };
  for (const auto& [name, damage, words] : cases) {
    const std::string bad = dir + "/" + name + ".h5";
    std::filesystem::copy_file(layer, bad);
    damage(LayerFile(bad));
    const auto b = test::run_app("build", "--config " + kConfig + " --layers 1 --in " + bad +
                                              " --out " + dir + "/b_" + name);
    EXPECT_EQ(b.status, 2) << name << ": " << b.err;
    EXPECT_EQ(b.err_lines(), 1) << name << ": " << b.err;
    EXPECT_NE(b.err.find(words), std::string::npos) << name << ": " << b.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/b_" + name)) << name;
    const auto d = test::run_app("deposit", "--config " + kScenes + "/spread.ini --seed 1 --in " +
                                                bad + " --out " + dir + "/d_" + name + ".h5");
    EXPECT_EQ(d.status, 2) << name << ": " << d.err;
    EXPECT_EQ(d.err_lines(), 1) << name << ": " << d.err;
    EXPECT_NE(d.err.find(words), std::string::npos) << name << ": " << d.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/d_" + name + ".h5")) << name;
  }
}

// A build whose scan scene is one track (no hatch, no path: the [GZ] defaults place it) judges
// lack of fusion along that track: its scanned area is the track's strip, 2 w wide along the
// plate's length (issue 32: NaN ends counted nothing as scanned).
TEST(BuildCli, SingleTrackBuildJudgesTheTracksStrip) {
  const std::string dir = test::scratch_dir("build_single_track");
  const auto r = test::run_app("build", "--config " + kConfig + " --sinter " + kScenes +
                                            "/scan-track.ini --layers 1 --json --out " + dir + "/run");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto at = r.out.find("\"scanned_area\":");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double area = std::stod(r.out.substr(at + 15));
  const bed::Bed bed = bed::read_bed_h5(dir + "/run/layer-001-spread.h5");
  const double w = 30e-6, grid = 20e-6;  // scan-track.ini's spot and grid
  // The strip's columns: (2w / dy + 1) rows along the plate, to a row either way.
  const double strip = bed.domain.length(0) * 2 * w;
  EXPECT_NEAR(area, strip + bed.domain.length(0) * grid, bed.domain.length(0) * grid) << r.out;
}

// build --map.power ... --map.speed ...: one spread of the first layer, a folder per point built
// from it, map.json with each point's energy density P / (v h t), its part's porosity and its
// regions; the points differ in the laser only, so a faster scan at the same power leaves pools
// no wider. The porosity judged is the interior's, no more than the whole part's. Bad grids and
// a map of one layer (no interior) exit 2 with one line and write nothing.
TEST(BuildCli, MapBuildsEveryPointFromOneSpread) {
  const std::string dir = test::scratch_dir("build_map");
  const std::string base = "--config " + kConfig + " --pictures false --threads 1 ";
  const auto r = test::run_app("build", base + "--layers 2 --map.power 100 --map.speed 0.5,1.5 --json --out " + dir + "/map");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir + "/map/layer-001-spread.h5"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/map/map.json"));
  for (const char* point : {"point-001", "point-002"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/map/" + point + "/layer-001-scan.h5")) << point;
    EXPECT_TRUE(std::filesystem::exists(dir + "/map/" + point + "/build.json")) << point;
    EXPECT_FALSE(std::filesystem::exists(dir + "/map/" + point + "/layer-001-spread.h5")) << point;
  }
  EXPECT_EQ(test::json_number(r.out, "points"), 2);
  const std::string second = r.out.substr(r.out.find("point-002"));
  const double hatch = test::json_number(r.out, "hatch"), layer = test::json_number(r.out, "layer");
  EXPECT_NEAR(test::json_number(r.out, "energy_density"), 100 / (0.5 * hatch * layer), 1e-6 * 100 / (0.5 * hatch * layer));
  EXPECT_GE(test::json_number(r.out, "porosity"), 0);
  EXPECT_LE(test::json_number(r.out, "porosity"), test::json_number(r.out, "whole_porosity"));
  EXPECT_GE(test::json_number(r.out, "mean_track_width"), test::json_number(second, "mean_track_width"));
  EXPECT_NE(r.out.find("\"regions\":[\""), std::string::npos) << r.out;
  const std::pair<std::string, std::string> cases[] = {
      {"--map.power '' --map.speed 1", "--map.power: no values"},
      {"--map.power 100,-5 --map.speed 1", "--map.power: '-5'"},
      {"--map.power 100,abc --map.speed 1", "--map.power: 'abc'"},
      {"--map.power 100", "one given without the other"},
      {"--map.power 100 --map.speed 1 --map.hatch 0", "--map.hatch"},
      {"--map.power 100 --map.speed 1 --sinter " + kScenes + "/scan-track.ini", "scans no hatch"},
      {"--map.power 100 --map.speed 1 --layers 1", "--layers: 1 with a map"},
  };
  for (const auto& [args, field] : cases) {
    const auto bad = test::run_app("build", base + args + " --out " + dir + "/bad");
    EXPECT_EQ(bad.status, 2) << args << ": " << bad.err;
    EXPECT_EQ(bad.err_lines(), 1) << args << ": " << bad.err;
    EXPECT_NE(bad.err.find(field), std::string::npos) << args << ": " << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad")) << args;
  }
}
