// The hostile-but-fair probe of issue 14 as a table (docs/hardening.md): each case runs one
// program on one bad input and checks the promise of docs/architecture.md "Command-line programs": exit 2
// (or the status the case names), ONE line on stderr naming the option/file/field, nothing on
// stdout, and the scratch folder exactly as it was (no output, no temporary, every existing file
// byte for byte). Files are made on demand: "@name" in a command is a file of the scratch folder
// built by make_file(name) (good beds, damaged beds, scene files, an old output, folders).
// Then the kill tests (SIGKILL / SIGINT while a program writes: the old output intact, no
// temporaries left).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"
#include "powderbed/dem/spread.hpp"
#include "run_command.hpp"

namespace {

namespace fs = std::filesystem;
using powderbed::test::CommandResult;

// ----------------------------------------------------------------------------------------------
// One case of the table.
struct Case {
  std::string name;                // unique, [A-Za-z0-9_]
  std::string app;                 // packgen, deposit, sinter, keff, bedstat, bedconv
  std::string args;                // "@file" -> scratch file; "{scenes}" -> data/scenes
  int status = 2;                  // expected exit status
  std::vector<std::string> words;  // each must appear on stderr ("@file" expands too)
};

std::ostream& operator<<(std::ostream& out, const Case& c) {
  return out << c.app << " " << c.args;
}

// ----------------------------------------------------------------------------------------------
// HDF5 damage (the writer refuses bad beds, so the C API edits a good file).
struct H5 {
  explicit H5(const std::string& path) : f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)) {}
  ~H5() { H5Fclose(f); }
  void remove(const char* name) const { H5Ldelete(f, name, H5P_DEFAULT); }
  void dataset(const char* name, hid_t file_type, hid_t mem_type, const void* data,
               std::vector<hsize_t> dims) const {
    remove(name);
    const hid_t space = dims.empty() ? H5Screate(H5S_SCALAR)
                                     : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
    const hid_t set = H5Dcreate2(f, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (data) H5Dwrite(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Dclose(set);
    H5Sclose(space);
  }
  void doubles(const char* name, const std::vector<double>& v, hsize_t cols) const {
    dataset(name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, v.data(),
            cols ? std::vector<hsize_t>{v.size() / cols, cols} : std::vector<hsize_t>{v.size()});
  }
  void attr_delete(const char* object, const char* name) const {
    H5Adelete_by_name(f, object, name, H5P_DEFAULT);
  }
  template <class T>
  void attr_numbers(const char* object, const char* name, hid_t type, const std::vector<T>& v) const {
    attr_delete(object, name);
    const hsize_t n = v.size();
    const hid_t space = n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr);
    const hid_t a = H5Acreate_by_name(f, object, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, type, v.data());
    H5Aclose(a);
    H5Sclose(space);
  }
  // A fixed-length string attribute of `count` copies of `value` (count 1: scalar).
  void attr_string(const char* object, const char* name, const std::string& value, hsize_t count = 1) const {
    attr_delete(object, name);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, value.size());
    const hid_t space = count == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr);
    const hid_t a = H5Acreate_by_name(f, object, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    std::string data;
    for (hsize_t i = 0; i < count; ++i) data += value;
    H5Awrite(a, type, data.data());
    H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
  }
  hid_t f;
};

powderbed::bed::Bed good_bed() { return powderbed::bed::simple_cubic_lattice(2, 1e-5); }  // 8, 40 um box

std::vector<double> rows_of(const powderbed::bed::Bed& b) {
  std::vector<double> rows;
  for (std::size_t i = 0; i < b.n(); ++i) rows.insert(rows.end(), {b.x[i], b.y[i], b.z[i]});
  return rows;
}

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

const char* kDumpHead = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n";
const char* kDumpBox = "ITEM: BOX BOUNDS ff ff ff\n0 4e-5\n0 4e-5\n0 4e-5\n";

// A layer file of the small build with one of issue 36's damages (layer_<damage>.h5), built in
// `dir`/layer_build (which stays: a refused run must leave it as it is too).
void make_layer_file(const std::string& dir, const std::string& name) {
  const std::string build = dir + "/layer_build", layer = build + "/layer-001.h5";
  if (!fs::exists(layer)) {
    const auto r = powderbed::test::run_app(
        "build", "--config " POWDERBED_TEST_DATA "/build-small/build.ini --layers 1 --out " + build);
    if (r.status != 0) throw std::runtime_error("the small build failed: " + r.err);
  }
  const std::string p = dir + "/" + name;
  fs::copy_file(layer, p);
  H5 h(p);
  const auto restart_dt = [&](double dt) { h.attr_numbers<double>("/restart", "dt", H5T_NATIVE_DOUBLE, {dt}); };
  if (name == "layer_dt_one.h5") restart_dt(1.0);
  if (name == "layer_dt_nan.h5") restart_dt(NAN);
  if (name == "layer_dt_zero.h5") restart_dt(0.0);
  if (name == "layer_no_restart.h5") h.remove("/restart");
  if (name == "layer_huge_pairs.h5") {
    h.dataset("/restart/pair_ids", H5T_STD_U64LE, H5T_NATIVE_UINT64, nullptr, {1000000000, 2});
  }
  if (name == "layer_in_solid.h5") {  // particle 0 a tenth of a radius above the plate, where
    const powderbed::bed::Bed bed = powderbed::bed::read_bed_h5(layer);  // the solid is highest
    const auto floor = powderbed::dem::read_spread_state(layer, bed).floor;
    const auto top = static_cast<std::size_t>(std::max_element(floor.z.begin(), floor.z.end()) - floor.z.begin());
    auto rows = rows_of(bed);
    rows[0] = floor.x0 + floor.dx * static_cast<double>(top % floor.nx);
    rows[1] = floor.y0 + floor.dy * static_cast<double>(top / floor.nx);
    rows[2] = bed.domain.lower[2] + 0.1 * bed.radius[0];
    h.doubles("/particles/position", rows, 3);
  }
}

// The scratch files a command can name, built on demand.
void make_file(const std::string& dir, const std::string& name) {
  const std::string p = dir + "/" + name;
  if (fs::exists(p)) return;
  namespace bed = powderbed::bed;
  auto damaged = [&](const std::function<void(H5&)>& edit) {
    bed::write_bed_h5(good_bed(), p);
    fs::remove(dir + "/" + name.substr(0, name.size() - 3) + ".xmf");
    H5 h(p);
    edit(h);
  };
  // Folders.
  if (name == "adir" || name == "side.xmf" || name == "prof-profile.csv") {
    fs::create_directories(p);
    return;
  }
  // Good beds and an existing output (which a failed run must leave as it is).
  if (name == "good.h5" || name == "old.h5") return bed::write_bed_h5(good_bed(), p);
  if (name == "wide.h5") {  // 0.4 x 0.4 mm floor: wider than gz2016-sinter's spot
    bed::Bed b;
    b.domain.upper = {4e-4, 4e-4, 1e-4};
    for (int i = 0; i < 8; ++i) b.add(2e-5 + 4e-5 * i, 2e-4, 1.5e-5, 1.5e-5);
    return bed::write_bed_h5(b, p);
  }
  if (name == "good2d.h5") {
    bed::Bed b;
    b.domain.dimension = 2;
    b.domain.upper = {1e-4, 1e-4, 0};
    for (int i = 0; i < 4; ++i) b.add(2e-5 + 2e-5 * i, 2e-5, 0, 1e-5);
    return bed::write_bed_h5(b, p);
  }
  if (name == "good.csv") return bed::write_bed_csv(good_bed(), p);
  if (name == "good.dump") {
    return write(p, std::string(kDumpHead) + "2\n" + kDumpBox +
                        "ITEM: ATOMS id x y z radius\n1 1e-5 1e-5 1e-5 1e-5\n2 3e-5 1e-5 1e-5 1e-5\n");
  }
  // Damaged HDF5 beds.
  if (name == "text.h5") return write(p, "this is not a bed\n");
  if (name == "empty.h5") return write(p, "");
  if (name == "truncated.h5") {
    bed::write_bed_h5(good_bed(), dir + "/full.tmpbed");
    std::ifstream in(dir + "/full.tmpbed", std::ios::binary);
    std::string head(3000, '\0');
    in.read(head.data(), 3000);
    head.resize(static_cast<std::size_t>(in.gcount()));
    in.close();
    fs::remove(dir + "/full.tmpbed");
    fs::remove(dir + "/full.xmf");
    return write(p, head);
  }
  const bed::Bed g = good_bed();
  if (name == "no_id.h5") return damaged([](H5& h) { h.remove("/particles/id"); });
  if (name == "no_domain.h5") return damaged([](H5& h) { h.remove("/domain"); });
  if (name == "no_version.h5") return damaged([](H5& h) { h.attr_delete("/", "version"); });
  if (name == "radius_count.h5")
    return damaged([](H5& h) { h.doubles("/particles/radius", std::vector<double>(7, 1e-5), 0); });
  if (name == "nan_position.h5") {
    return damaged([&](H5& h) {
      auto rows = rows_of(g);
      rows[6] = NAN;
      h.doubles("/particles/position", rows, 3);
    });
  }
  if (name == "negative_radius.h5") {
    return damaged([&](H5& h) {
      auto r = g.radius;
      r[4] = -1e-5;
      h.doubles("/particles/radius", r, 0);
    });
  }
  if (name == "version2.h5")
    return damaged([](H5& h) { h.attr_numbers<int>("/", "version", H5T_NATIVE_INT, {2}); });
  if (name == "format_other.h5")
    return damaged([](H5& h) { h.attr_string("/", "format", "other.format"); });
  if (name == "format_array.h5")
    return damaged([](H5& h) { h.attr_string("/", "format", "powderbed.bed", 1000); });
  if (name == "format_number.h5")
    return damaged([](H5& h) { h.attr_numbers<int>("/", "format", H5T_NATIVE_INT, {7}); });
  if (name == "unit_mm.h5") return damaged([](H5& h) { h.attr_string("/", "length_unit", "mm"); });
  if (name == "dimension4.h5")
    return damaged([](H5& h) { h.attr_numbers<int>("/", "dimension", H5T_NATIVE_INT, {4}); });
  if (name == "flat_domain.h5") {
    return damaged([](H5& h) {
      h.attr_numbers<double>("/domain", "upper", H5T_NATIVE_DOUBLE, {4e-5, 4e-5, 0});
    });
  }
  if (name == "upper_short.h5")
    return damaged([](H5& h) { h.attr_numbers<double>("/domain", "upper", H5T_NATIVE_DOUBLE, {4e-5, 4e-5}); });
  if (name == "periodic5.h5") {
    return damaged([](H5& h) {
      h.attr_numbers<std::uint8_t>("/domain", "periodic", H5T_NATIVE_UINT8, {5, 0, 0});
    });
  }
  if (name == "huge_rows.h5") {  // 2e9 rows declared, none stored: a few KB on disk
    return damaged([](H5& h) {
      h.dataset("/particles/position", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, nullptr, {2000000000, 3});
    });
  }
  if (name == "huge_ids.h5") {
    return damaged([](H5& h) {
      h.dataset("/particles/id", H5T_STD_U64LE, H5T_NATIVE_UINT64, nullptr, {200000000});
    });
  }
  if (name == "position_rank1.h5")
    return damaged([&](H5& h) { h.doubles("/particles/position", rows_of(g), 0); });
  if (name == "position_scalar.h5") {
    return damaged([](H5& h) {
      const double v = 1e-5;
      h.dataset("/particles/position", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &v, {});
    });
  }
  if (name == "float_ids.h5") {
    return damaged([](H5& h) { h.doubles("/particles/id", std::vector<double>(8, 1.0), 0); });
  }
  if (name == "um_radii.h5") {  // radii in micrometres: 10 "m" in a 40 um box
    return damaged([](H5& h) { h.doubles("/particles/radius", std::vector<double>(8, 10.0), 0); });
  }
  if (name == "far_particle.h5") {  // one centre at (1, 1, 1) m in a 40 um box
    return damaged([&](H5& h) {
      auto rows = rows_of(g);
      rows[9] = rows[10] = rows[11] = 1.0;
      h.doubles("/particles/position", rows, 3);
    });
  }
  if (name == "below_floor.h5") {  // a centre 3 radii below the floor
    return damaged([&](H5& h) {
      auto rows = rows_of(g);
      rows[2] = -3e-5;
      h.doubles("/particles/position", rows, 3);
    });
  }
  if (name == "material_big.h5") {
    return damaged([](H5& h) {
      const std::vector<std::int32_t> m(8, 70000);
      h.dataset("/particles/material", H5T_STD_I32LE, H5T_NATIVE_INT32, m.data(), {8});
    });
  }
  if (name == "material_negative.h5") {
    return damaged([](H5& h) {
      const std::vector<std::int32_t> m(8, -1);
      h.dataset("/particles/material", H5T_STD_I32LE, H5T_NATIVE_INT32, m.data(), {8});
    });
  }
  if (name == "id_negative.h5") {
    return damaged([](H5& h) {
      const std::vector<std::int64_t> id = {0, 1, 2, 3, 4, 5, 6, -7};
      h.dataset("/particles/id", H5T_STD_I64LE, H5T_NATIVE_INT64, id.data(), {8});
    });
  }
  if (name == "duplicate_ids.h5") {
    return damaged([](H5& h) {
      const std::vector<std::uint64_t> id = {0, 1, 2, 3, 4, 5, 6, 6};
      h.dataset("/particles/id", H5T_STD_U64LE, H5T_NATIVE_UINT64, id.data(), {8});
    });
  }
  if (name == "phase7.h5") {
    return damaged([](H5& h) {
      const std::vector<std::uint8_t> ph(8, 7);
      h.dataset("/particles/phase", H5T_STD_U8LE, H5T_NATIVE_UINT8, ph.data(), {8});
    });
  }
  if (name == "z_in_2d.h5") {
    bed::Bed b;
    b.domain.dimension = 2;
    b.domain.upper = {1e-4, 1e-4, 0};
    for (int i = 0; i < 4; ++i) b.add(2e-5 + 2e-5 * i, 2e-5, 0, 1e-5);
    bed::write_bed_h5(b, p);
    fs::remove(dir + "/z_in_2d.xmf");
    H5 h(p);
    std::vector<double> rows = rows_of(b);
    rows[2] = 1e-6;
    h.doubles("/particles/position", rows, 3);
    return;
  }
  // Damaged CSV beds (domain 0..4e-5 given with --domain).
  const std::map<std::string, std::string> csv = {
      {"csv_header.csv", "a,b,c,d\n1e-5,1e-5,1e-5,1e-5\n"},
      {"csv_three.csv", "x,y,z,r\n1e-5,1e-5,1e-5,1e-5\n2e-5,2e-5,2e-5\n"},
      {"csv_five.csv", "x,y,z,r\n1e-5,1e-5,1e-5,1e-5,1\n"},
      {"csv_word.csv", "x,y,z,r\n1e-5,one,1e-5,1e-5\n"},
      {"csv_nan.csv", "x,y,z,r\n1e-5,nan,1e-5,1e-5\n"},
      {"csv_inf.csv", "x,y,z,r\n1e-5,1e-5,inf,1e-5\n"},
      {"csv_r0.csv", "x,y,z,r\n1e-5,1e-5,1e-5,0\n"},
      {"csv_rneg.csv", "x,y,z,r\n1e-5,1e-5,1e-5,-1e-5\n"},
      {"csv_far.csv", "x,y,z,r\n1e-5,1e-5,1e-5,1e-5\n1,1,1,1e-5\n"},
      {"csv_um.csv", "x,y,z,r\n10,10,10,10\n"},
      {"csv_empty.csv", ""},
  };
  if (auto it = csv.find(name); it != csv.end()) return write(p, it->second);
  // Damaged LAMMPS dumps.
  const std::string atoms = "ITEM: ATOMS id x y z radius\n";
  const std::map<std::string, std::string> dump = {
      {"dump_no_timestep.dump", "hello\n"},
      {"dump_huge_count.dump", std::string(kDumpHead) + "2000000000\n" + kDumpBox + atoms +
                                   "1 1e-5 1e-5 1e-5 1e-5\n"},
      {"dump_count_word.dump", std::string(kDumpHead) + "many\n" + kDumpBox + atoms},
      {"dump_truncated.dump", std::string(kDumpHead) + "3\n" + kDumpBox + atoms +
                                  "1 1e-5 1e-5 1e-5 1e-5\n2 3e-5 1e-5 1e-5 1e-5\n"},
      {"dump_no_radius.dump", std::string(kDumpHead) + "1\n" + kDumpBox +
                                  "ITEM: ATOMS id x y z\n1 1e-5 1e-5 1e-5\n"},
      {"dump_triclinic.dump", std::string(kDumpHead) + "1\n" +
                                  "ITEM: BOX BOUNDS xy xz yz ff ff ff\n0 4e-5 0\n0 4e-5 0\n0 4e-5 0\n" +
                                  atoms + "1 1e-5 1e-5 1e-5 1e-5\n"},
      {"dump_word.dump", std::string(kDumpHead) + "1\n" + kDumpBox + atoms + "1 1e-5 abc 1e-5 1e-5\n"},
      {"dump_id0.dump", std::string(kDumpHead) + "1\n" + kDumpBox + atoms + "0 1e-5 1e-5 1e-5 1e-5\n"},
      {"dump_um.dump", std::string(kDumpHead) + "1\n" + kDumpBox + atoms + "1 1e-5 1e-5 1e-5 20\n"},
      {"dump_far.dump", std::string(kDumpHead) + "1\n" + kDumpBox + atoms + "1 1 1 1 1e-5\n"},
      {"dump_bad_box.dump", std::string(kDumpHead) + "1\n" +
                                "ITEM: BOX BOUNDS ff ff ff\n4e-5 0\n0 4e-5\n0 4e-5\n" + atoms +
                                "1 1e-5 1e-5 1e-5 1e-5\n"},
      {"dump_extra.dump", std::string(kDumpHead) + "1\n" + kDumpBox + atoms +
                              "1 1e-5 1e-5 1e-5 1e-5\n2 1e-5 1e-5 1e-5 1e-5\n"},
  };
  if (auto it = dump.find(name); it != dump.end()) return write(p, it->second);
  // Damaged foreign formats (docs/decks.md).
  const std::map<std::string, std::string> foreign = {
      {"cut.data", "title\n\n2 atoms\n1 atom types\n0 4e-5 xlo xhi\n0 4e-5 ylo yhi\n0 4e-5 zlo zhi\n\n"
                   "Atoms # sphere\n\n1 1 2e-5 7952 1e-5 1e-5 1e-5\n"},
      {"bad_yade.txt", "#format x_y_z_r\n1e-5 1e-5 1e-5\n"},
      {"bad.geo", "LSMGeometry 0.1\n"},
      {"bad.dump.gz", std::string("\x1f\x8b\x08\x00garbage", 11)},
  };
  if (auto it = foreign.find(name); it != foreign.end()) return write(p, it->second);
  // Scene files.
  const std::map<std::string, std::string> ini = {
      {"unknown_key.ini", "# a scene\n[nosuch]\nkey = 1\n"},
      {"no_equals.ini", "just some words\n"},
      {"open_section.ini", "[laser\n"},
      {"seed_negative.ini", "\n\nseed = -1\n"},
      {"threads_negative.ini", "threads = -2\n"},
      {"nan_value.ini", "# doubles refuse nan\ntol = nan\n"},
      {"nested_config.ini", "config = other.ini\n"},
      {"packgen_count.ini", "# count\n\ncount = -5\n"},
      {"bad_escape.ini", "# a scene\nseed = \"a\\qb\"\n"},
      {"open_quote.ini", "seed = \"12\n"},
  };
  if (auto it = ini.find(name); it != ini.end()) return write(p, it->second);
  // What is not a regular file (issue 36): a FIFO (a reader that opens it blocks until a
  // writer comes) and links to /dev/zero (a reader never reaches its end).
  if (name.rfind("fifo", 0) == 0) {
    ::mkfifo(p.c_str(), 0600);
    return;
  }
  if (name.rfind("zero", 0) == 0 && name.find(".gz") == std::string::npos)
    return fs::create_symlink("/dev/zero", p);
  // 4 MB of zeros gzipped (about 4 KB): inside the memory guard, so it is inflated, then refused
  // as a dump (test_io.cpp checks a stream inflating past the guard against a small guard).
  if (name == "zeros.dump.gz") {
    const std::string cmd = "head -c 4000000 /dev/zero | gzip -c > '" + p + "'";
    if (std::system(cmd.c_str()) != 0) ADD_FAILURE() << cmd;
    return;
  }
  // Material files without what every run of a program reads (data/materials/316L.csv less a
  // line), empty, binary.
  if (name == "mat_no_density.csv" || name == "mat_no_melting.csv") {
    const std::string drop = name == "mat_no_density.csv" ? "density," : "melting_point,";
    std::ifstream in(std::string(POWDERBED_SOURCE_DIR) + "/data/materials/316L.csv");
    std::ofstream out(p);
    for (std::string line; std::getline(in, line);)
      if (line.rfind(drop, 0) != 0) out << line << '\n';
    return;
  }
  if (name == "mat_empty.csv") return write(p, "");
  if (name == "mat_binary.csv" || name == "binary.ini") {
    const char bytes[] = "\x7f" "ELF\x02\x01\x01\0\0\0\x1b[31m\r,\xff\xfe\n\x01\x02\n";
    return write(p, std::string(bytes, sizeof bytes - 1));
  }
  // A --deck-scene with a line that is not key = value, and with a key deposit does not know.
  if (name == "deck_garbage.ini") return write(p, "[material]\ndamping 0.7\n");
  if (name == "deck_unknown.ini") return write(p, "[material]\nfoo = 1\n");
  if (name == "nan_density.data") {
    return write(p, "title\n\n1 atoms\n1 atom types\n0 4e-5 xlo xhi\n0 4e-5 ylo yhi\n0 4e-5 zlo zhi\n\n"
                    "Atoms # sphere\n\n1 1 2e-5 nan 2e-5 2e-5 2e-5\n");
  }
  // A scan path whose one row asks for a gigawatt (inside wide.h5's 0.4 mm floor).
  if (name == "gigawatt_scan.csv")
    return write(p, "x0,y0,x1,y1,power,speed\n50e-6,200e-6,350e-6,200e-6,1e9,1\n");
  // Layer files of the small build (tests/data/build-small, ~1 s), damaged as issue 36's probe
  // damaged them.
  if (name.rfind("layer_", 0) == 0) return make_layer_file(dir, name);
  // Any other name (out.h5, new.csv, missing.h5, nowhere/...) is meant not to exist.
}

// ----------------------------------------------------------------------------------------------
// The table.
std::vector<Case> all_cases() {
  std::vector<Case> t;
  auto add = [&](std::string name, std::string app, std::string args, int status,
                 std::vector<std::string> words) {
    t.push_back({std::move(name), std::move(app), std::move(args), status, std::move(words)});
  };
  const std::string pk = "--dim 3 --domain 1e-4,1e-4,1e-4 --psd mono:d=2e-5 ";
  const std::string pk_ok = pk + "--seed 1 --out @new.h5";
  const std::string sinter = "--config {scenes}/gz2016-sinter.ini ";
  const std::string keff = "";
  const std::string deposit = "--t-end 1e-5 --seed 1 ";

  // Every program: the shared conventions.
  const std::vector<std::pair<std::string, std::string>> programs = {
      {"packgen", pk + "--seed 1 --out @out.h5 "},
      {"bedstat", "@good.h5 "},
      {"bedconv", "@good.h5 @out.csv "},
      {"deposit", "--in @good.h5 " + deposit + "--out @out.h5 "},
      {"sinter", "--bed @wide.h5 --out @out.h5 "},
      {"keff", "--bed @good.h5 --out @out.h5 "},
  };
  for (const auto& [app, base] : programs) {
    add(app + "_unknown_option", app, base + "--bogus 1", 2, {"bogus"});
    add(app + "_config_missing", app, base + "--config @nowhere/scene.ini", 2, {"scene.ini"});
    add(app + "_config_folder", app, base + "--config @adir", 2, {"adir"});
    add(app + "_config_unknown_key", app, base + "--config @unknown_key.ini", 2,
        {"unknown_key.ini:3", "nosuch.key"});
    add(app + "_config_no_equals", app, base + "--config @no_equals.ini", 2, {"no_equals.ini:1"});
    add(app + "_config_open_section", app, base + "--config @open_section.ini", 2,
        {"open_section.ini:1", "[laser"});
    add(app + "_config_nested", app, base + "--config @nested_config.ini", 2,
        {"nested_config.ini:1", "config"});
    add(app + "_config_fifo", app, base + "--config @fifo.ini", 2, {"--config", "@fifo.ini", "FIFO"});
    add(app + "_config_dev_null", app, base + "--config /dev/null", 2,
        {"--config", "/dev/null", "character device"});
    add(app + "_config_bad_escape", app, base + "--config @bad_escape.ini", 2,
        {"bad_escape.ini:2", "unknown escape"});
    add(app + "_config_open_quote", app, base + "--config @open_quote.ini", 2,
        {"open_quote.ini:1", "closed before the line ends"});
    add(app + "_help", app, "--help", 0, {});
    add(app + "_version", app, "--version", 0, {});
  }
  // Numbers with a sign, a range and a type, in every program that takes them.
  for (const auto& [app, base, option] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"packgen", pk + "--out @out.h5 ", "--seed"},
           {"deposit", "--in @good.h5 --t-end 1e-5 --out @out.h5 ", "--seed"},
           {"keff", "--bed @good.h5 --out @out.h5 ", "--radiation.seed"},
           {"sinter", sinter + "--bed @wide.h5 --out @out.h5 ", "--laser.ray-seed"}}) {
    add(app + "_seed_negative", app, base + option + " -1", 2, {option, "-1", "negative"});
    add(app + "_seed_fraction", app, base + option + " 1.5", 2, {option, "1.5", "whole number"});
    add(app + "_seed_word", app, base + option + " abc", 2, {option, "abc"});
    add(app + "_seed_too_big", app, base + option + " 1e30", 2, {option, "1e30", "range"});
  }
  for (const auto& [app, base] : std::vector<std::pair<std::string, std::string>>{
           {"deposit", "--in @good.h5 " + deposit + "--out @out.h5 "},
           {"sinter", "--bed @wide.h5 --out @out.h5 "}}) {
    add(app + "_threads_negative", app, base + "--threads -1", 2, {"--threads", "-1", "0 to"});
    add(app + "_threads_word", app, base + "--threads many", 2, {"--threads", "many"});
    add(app + "_threads_ini", app, base + "--config @threads_negative.ini", 2, {"threads", "-2"});
  }

  // Bed files: every damage, through every program that reads a bed.
  const std::vector<std::tuple<std::string, std::vector<std::string>>> damage = {
      {"text", {"not an HDF5 file"}},
      {"empty", {"not an HDF5 file"}},
      {"truncated", {"truncated"}},
      {"no_id", {"/particles/id", "missing"}},
      {"no_domain", {"/domain", "missing"}},
      {"no_version", {"version", "missing"}},
      {"radius_count", {"/particles/radius", "rows"}},
      {"nan_position", {"position x[2]", "nan"}},
      {"negative_radius", {"radius[4]", "> 0"}},
      {"version2", {"version 2"}},
      {"format_other", {"format", "other.format"}},
      {"format_array", {"format", "1000 values"}},
      {"format_number", {"format", "not a string"}},
      {"unit_mm", {"length_unit", "mm"}},
      {"dimension4", {"dimension", "4"}},
      {"flat_domain", {"domain axis z"}},
      {"upper_short", {"upper", "2 values"}},
      {"periodic5", {"periodic[0]", "5"}},
      {"huge_rows", {"/particles/position", "2000000000 rows"}},
      {"huge_ids", {"/particles/id", "200000000 rows"}},
      {"position_rank1", {"/particles/position", "shape"}},
      {"position_scalar", {"/particles/position", "shape"}},
      {"float_ids", {"/particles/id", "not integer"}},
      {"um_radii", {"radius[0]", "um"}},
      {"far_particle", {"particle 3", "outside the domain"}},
      {"below_floor", {"particle 0", "outside the domain"}},
      {"material_big", {"/particles/material", "0 to 65535"}},
      {"material_negative", {"/particles/material", "0 to 65535"}},
      {"id_negative", {"/particles/id", "range"}},
      {"duplicate_ids", {"id 6", "twice"}},
      {"phase7", {"phase[0]", "7"}},
      {"z_in_2d", {"z of particle 0", "2D"}},
  };
  for (const auto& [kind, words] : damage) {
    std::vector<std::string> w = words;
    w.push_back("@" + kind + ".h5");
    add("bedstat_bed_" + kind, "bedstat", "@" + kind + ".h5 --json", 2, w);
    add("bedconv_bed_" + kind, "bedconv", "@" + kind + ".h5 @out.csv", 2, w);
    add("sinter_bed_" + kind, "sinter", sinter + "--bed @" + kind + ".h5 --out @out.h5", 2, w);
    add("keff_bed_" + kind, "keff", "--bed @" + kind + ".h5 --out @out.h5", 2, w);
    add("deposit_bed_" + kind, "deposit", "--in @" + kind + ".h5 " + deposit + "--out @out.h5", 2, w);
  }
  const std::string dom = " --domain 0,0,0,4e-5,4e-5,4e-5";
  const std::vector<std::tuple<std::string, std::vector<std::string>>> csv_damage = {
      {"csv_header", {":1:", "header"}},
      {"csv_three", {":3:", "3 fields"}},
      {"csv_five", {":2:", "5 fields"}},
      {"csv_word", {":2:", "one"}},
      {"csv_nan", {":2:", "nan"}},
      {"csv_inf", {":2:", "inf"}},
      {"csv_r0", {":2:", "r is 0"}},
      {"csv_rneg", {":2:", "> 0"}},
      {"csv_far", {"particle 1", "outside the domain"}},
      {"csv_um", {"radius[0]", "um"}},
      {"csv_empty", {"header"}},
  };
  for (const auto& [kind, words] : csv_damage) {
    std::vector<std::string> w = words;
    w.push_back("@" + kind + ".csv");
    add("bedstat_" + kind, "bedstat", "@" + kind + ".csv --json" + dom, 2, w);
    add("bedconv_" + kind, "bedconv", "@" + kind + ".csv @out.h5" + dom, 2, w);
  }
  const std::vector<std::tuple<std::string, std::vector<std::string>>> dump_damage = {
      {"dump_no_timestep", {"ITEM: TIMESTEP"}},
      {"dump_huge_count", {"2000000000", "bytes follow"}},
      {"dump_count_word", {"number of atoms", "many"}},
      {"dump_truncated", {"2 of 3 atoms"}},
      {"dump_no_radius", {"radius|diameter"}},
      {"dump_triclinic", {"triclinic"}},
      {"dump_word", {"column y", "abc"}},
      {"dump_id0", {"id is '0'"}},
      {"dump_um", {"radius[0]", "um"}},
      {"dump_far", {"particle 0", "outside the domain"}},
      {"dump_bad_box", {"box bounds", "lower < upper"}},
      {"dump_extra", {"unexpected line"}},
  };
  for (const auto& [kind, words] : dump_damage) {
    std::vector<std::string> w = words;
    w.push_back("@" + kind + ".dump");
    add("bedstat_" + kind, "bedstat", "@" + kind + ".dump --json", 2, w);
    add("bedconv_" + kind, "bedconv", "@" + kind + ".dump @out.h5", 2, w);
  }
  // Not a regular file (issue 36): a FIFO in every reader, /dev/zero as a text bed; a gzip
  // stream that inflates to 4 MB of zeros (inflated within the guard, then refused as a dump).
  for (const std::string ext : {".h5", ".csv", ".dump", ".lammpstrj", ".data", ".txt", ".geo", ".dump.gz"}) {
    std::string kind = ext.substr(1);
    std::replace(kind.begin(), kind.end(), '.', '_');
    add("bedconv_fifo_" + kind, "bedconv", "@fifo" + ext + " @out.h5" + (ext == ".csv" ? dom : ""), 2,
        {"@fifo" + ext, "FIFO", "regular file"});
  }
  add("bedstat_fifo_h5", "bedstat", "@fifo.h5 --json", 2, {"@fifo.h5", "FIFO"});
  add("bedstat_dev_zero_csv", "bedstat", "@zero.csv --json" + dom, 2, {"@zero.csv", "character device"});
  add("bedconv_dev_zero_dump", "bedconv", "@zero.dump @out.h5", 2, {"@zero.dump", "character device"});
  add("bedconv_gz_zeros", "bedconv", "@zeros.dump.gz @out.h5", 2, {"@zeros.dump.gz", "ITEM: TIMESTEP"});
  add("bedstat_gz_zeros", "bedstat", "@zeros.dump.gz --json", 2, {"@zeros.dump.gz", "ITEM: TIMESTEP"});
  add("deposit_in_fifo", "deposit", "--in @fifo.h5 " + deposit + "--out @out.h5", 2, {"--in", "@fifo.h5", "FIFO"});
  add("deposit_in_dev_zero", "deposit", "--in @zero.csv " + deposit + "--out @out.h5", 2,
      {"--in", "@zero.csv", "character device"});
  add("sinter_bed_fifo", "sinter", sinter + "--bed @fifo.h5 --out @out.h5", 2, {"--bed", "@fifo.h5", "FIFO"});
  add("keff_bed_fifo", "keff", "--bed @fifo.h5 --out @out.h5", 2, {"--bed", "@fifo.h5", "FIFO"});
  add("sinter_scan_path_fifo", "sinter", sinter + "--bed @wide.h5 --scan-path @fifo_scan.csv --out @out.h5", 2,
      {"--scan-path", "@fifo_scan.csv", "FIFO"});
  add("sinter_scan_path_dev_zero", "sinter", sinter + "--bed @wide.h5 --scan-path /dev/zero --out @out.h5", 2,
      {"--scan-path", "/dev/zero", "character device"});
  add("packgen_psd_table_fifo", "packgen",
      "--dim 3 --domain 1e-4,1e-4,1e-4 --psd table:file=@fifo_psd.csv --seed 1 --out @out.h5", 2,
      {"@fifo_psd.csv", "FIFO"});
  add("build_in_fifo", "build", "--config {scenes}/build-316L.ini --layers 1 --in @fifo.h5 --out @run", 2,
      {"--in", "@fifo.h5", "FIFO"});
  add("bedconv_deck_scene_fifo", "bedconv", "@good.h5 @out.data --deck lammps --deck-scene @fifo.ini", 2,
      {"--deck-scene", "@fifo.ini", "FIFO"});
  add("bedstat_config_binary", "bedstat", "@good.h5 --config @binary.ini", 2, {"binary.ini:1", "\\x7fELF"});

  // Material files (issue 36): not a file, without a key every run reads, empty, binary.
  const std::string dep_in = "--in @good.h5 " + deposit;
  add("deposit_material_dev_zero", "deposit", dep_in + "--material /dev/zero --out @out.h5", 2,
      {"--material", "/dev/zero", "character device"});
  add("sinter_material_fifo", "sinter", sinter + "--bed @wide.h5 --material @fifo_mat.csv --out @out.h5", 2,
      {"--material", "@fifo_mat.csv", "FIFO"});
  add("keff_material_dev_zero", "keff", "--bed @good.h5 --material @zero_mat.csv --out @out.h5", 2,
      {"--material", "@zero_mat.csv", "character device"});
  add("deposit_material_no_density", "deposit", dep_in + "--material @mat_no_density.csv --out @out.h5", 2,
      {"--material", "@mat_no_density.csv", "no density", "material.density"});
  add("sinter_material_no_melting_point", "sinter",
      "--bed @wide.h5 --material @mat_no_melting.csv --out @out.h5", 2,
      {"--material", "@mat_no_melting.csv", "no melting_point", "material.melting-point"});
  add("deposit_material_empty", "deposit", dep_in + "--material @mat_empty.csv --out @out.h5", 2,
      {"--material", "@mat_empty.csv", "no density"});
  add("sinter_material_empty", "sinter", "--bed @wide.h5 --material @mat_empty.csv --out @out.h5", 2,
      {"--material", "@mat_empty.csv", "no property table", "material.table"});
  add("keff_material_empty", "keff", "--bed @good.h5 --material @mat_empty.csv --out @out.h5", 2,
      {"--material", "@mat_empty.csv", "no property table", "solid.conductivity"});
  add("sinter_material_empty_over_scene", "sinter",
      sinter + "--bed @wide.h5 --material @mat_empty.csv --out @out.h5", 2,
      {"--material", "@mat_empty.csv", "no property table", "material.table"});
  add("deposit_material_binary", "deposit", dep_in + "--material @mat_binary.csv --out @out.h5", 2,
      {"--material", "@mat_binary.csv:1", "\\x7fELF\\x02", "\\x1b"});

  // bedconv --deck-scene is read as deposit's scene file; a LAMMPS data file's density.
  add("bedconv_deck_scene_garbage", "bedconv", "@good.h5 @out.data --deck lammps --deck-scene @deck_garbage.ini", 2,
      {"deck_garbage.ini:2", "damping 0.7", "key = value"});
  add("bedconv_deck_scene_unknown_key", "bedconv",
      "@good.h5 @out.data --deck lammps --deck-scene @deck_unknown.ini", 2, {"deck_unknown.ini:2", "material.foo"});
  add("bedconv_data_density_nan", "bedconv", "@nan_density.data @out.h5", 2, {"@nan_density.data", "density", "nan"});

  // build, sinter and keff before any work (issue 36): --out, the stages' own options, counts and
  // powers that hung or ran, walls beyond the solid.
  const std::string bld = "--config {scenes}/build-316L.ini --layers 1 ";
  add("build_out_empty", "build", bld + "--out ''", 2, {"--out: empty"});
  // 250 characters: a name the file system takes, but not with a temporary's suffix on it.
  add("build_out_too_long", "build", bld + "--out @" + std::string(250, 'r'), 2, {"--out", "250 characters long"});
  add("build_out_unmakeable", "build", bld + "--out /proc/powderbed_run", 2, {"--out", "cannot make the folder"});
  add("build_spread_args_in", "build", bld + "--out @run --spread-args '--in @good.h5'", 2,
      {"--spread-args", "'--in' is set by the build itself"});
  add("build_sinter_args_bed_out", "build", bld + "--out @run --sinter-args '--bed @good.h5 --out @o.h5'", 2,
      {"--sinter-args", "'--bed' is set by the build itself"});
  add("build_sinter_args_melt_fraction", "build", bld + "--out @run --sinter-args --fuse.melt-fraction=0.3", 2,
      {"--sinter-args", "'--fuse.melt-fraction'"});
  add("build_layers_wrap", "build", bld + "--out @run --layers 18446744073709551615", 2, {"--layers"});
  add("build_config_bad_escape", "build", bld + "--out @run --spread @bad_escape.ini", 2,
      {"bad_escape.ini:2", "unknown escape"});
  add("sinter_tracks_1e12", "sinter", sinter + "--bed @wide.h5 --scan.hatch 30e-6 --scan.tracks 1e12 --out @out.h5",
      2, {"scan.tracks", "1000000000000 tracks"});
  add("sinter_scan_row_gigawatt", "sinter", sinter + "--bed @wide.h5 --scan-path @gigawatt_scan.csv --out @out.h5",
      2, {"--scan-path", "segment 1", "1e+09 W"});
  add("sinter_melt_fraction_without_fuse", "sinter", sinter + "--bed @wide.h5 --fuse.melt-fraction 0.7 --out @out.h5",
      2, {"--fuse.melt-fraction", "without --fuse"});
  add("build_sinter_args_level", "build", bld + "--out @run --sinter-args --fuse.level=1e-5", 2,
      {"--sinter-args", "'--fuse.level'"});
  add("sinter_region_off_plate", "sinter",
      sinter + "--bed @wide.h5 --scan.hatch 30e-6 --scan.region 0,1e-3,0,0.4e-3 --out @out.h5", 2,
      {"--scan.region", "leaves the plate"});
  add("sinter_9900W_drills_through", "sinter", sinter + "--bed @wide.h5 --power 9900 --speed 1 --out @out.h5", 3,
      {"depression reached the substrate's bottom", "substrate.depth"});
  add("keff_t_hot_above_solidus", "keff",
      "--bed @good.h5 --material 316L --gas.model constant --t-hot 1e5 --out @out.h5", 2, {"--t-hot", "solidus"});
  add("keff_temperature_above_solidus", "keff",
      "--bed @good.h5 --material 316L --gas.model constant --temperature 1700 --out @out.h5", 2, {"--t-hot", "solidus"});
  // Every program: an output name the file system cannot hold with its temporary's suffix.
  const std::string long_h5 = "@" + std::string(250, 'o') + ".h5";
  add("packgen_out_too_long", "packgen", pk + "--seed 1 --out " + long_h5, 2, {"--out", "characters long"});
  add("deposit_out_too_long", "deposit", "--in @good.h5 " + deposit + "--out " + long_h5, 2,
      {"--out", "characters long"});
  add("sinter_out_too_long", "sinter", sinter + "--bed @wide.h5 --out " + long_h5, 2, {"--out", "characters long"});
  add("keff_out_too_long", "keff", "--bed @good.h5 --out " + long_h5, 2, {"--out", "characters long"});
  add("bedconv_out_too_long", "bedconv", "@good.h5 " + long_h5, 2, {"characters long"});

  // A layer file that cannot be continued, refused by both programs that continue one before
  // anything runs (issue 36: a 1 s step spread to z = -2e39 m; 1e9 declared pairs: bad_alloc).
  // The run's own checks (step, particles) name --in; the reader's name the file as well.
  const std::vector<std::pair<std::string, std::vector<std::string>>> layers = {
      {"dt_one", {"--in", "stable bound"}},
      {"dt_nan", {"@layer_dt_nan.h5", "dt is nan"}},
      {"dt_zero", {"@layer_dt_zero.h5", "dt is 0"}},
      {"no_restart", {"@layer_no_restart.h5", "/restart"}},
      {"huge_pairs", {"@layer_huge_pairs.h5", "declares 1000000000 rows"}},
      {"in_solid", {"--in", "inside the solid"}}};
  for (const auto& [kind, with_file] : layers) {
    const std::string file = "@layer_" + kind + ".h5";
    add("build_in_layer_" + kind, "build",
        "--config {testdata}/build-small/build.ini --layers 1 --in " + file + " --out @run", 2, with_file);
    add("deposit_in_layer_" + kind, "deposit",
        "--config {testdata}/build-small/spread.ini --seed 1 --in " + file + " --out @out.h5", 2, with_file);
  }

  // Paths: missing, folders, outputs that cannot be written, outputs that are inputs.
  add("bedstat_bed_missing", "bedstat", "@missing.h5", 2, {"@missing.h5", "does not exist"});
  add("bedstat_bed_folder", "bedstat", "@adir", 2, {"@adir", "folder"});
  add("bedstat_no_bed", "bedstat", "--json", 2, {"no bed"});
  add("bedstat_data_input", "bedstat", "@good.data", 2, {"does not exist"});
  add("bedconv_in_missing", "bedconv", "@missing.h5 @out.csv", 2, {"@missing.h5", "does not exist"});
  add("bedconv_in_folder", "bedconv", "@adir @out.csv", 2, {"@adir"});
  add("bedconv_out_is_in", "bedconv", "@good.h5 @good.h5", 2, {"@good.h5", "overwrite the input"});
  add("bedconv_out_is_in_path", "bedconv", "@good.h5 @adir/../good.h5", 2, {"overwrite the input"});
  add("bedconv_out_xmf_of_in", "bedconv", "@good.h5 @good.xmf", 2, {".xmf"});
  add("bedconv_out_dump", "bedconv", "@good.h5 @out.dump", 2, {"OUT", ".dump"});
  add("bedconv_out_txt", "bedconv", "@good.h5 @out.txt", 2, {"OUT", ".txt", ".h5"});
  add("bedconv_in_data_missing", "bedconv", "@good.data @out.h5", 2, {"@good.data", "does not exist"});
  add("bedconv_in_txt_missing", "bedconv", "@good.txt @out.h5", 2, {"@good.txt", "does not exist"});
  add("bedconv_in_xyz", "bedconv", "@good.xyz @out.h5", 2, {"IN", ".xyz", ".lammpstrj"});
  add("bedconv_out_no_folder", "bedconv", "@good.h5 @nowhere/out.csv", 2, {"nowhere", "does not exist"});
  add("bedconv_out_folder", "bedconv", "@good.h5 @adir/", 2, {"adir", "folder"});
  add("bedconv_out_sidecar_folder", "bedconv", "@good.h5 @side.h5", 2, {"side.xmf", "folder"});
  add("bedconv_old_output_kept", "bedconv", "@um_radii.h5 @old.h5", 2, {"um"});
  add("bedconv_density_negative", "bedconv", "@good.h5 @out.data --density -5", 2, {"--density", "-5"});
  add("bedconv_density_nan", "bedconv", "@good.h5 @out.data --density nan", 2, {"--density", "nan"});
  add("bedconv_density_not_data", "bedconv", "@good.h5 @out.csv --density 7900", 2, {"--density", ".data"});
  add("bedconv_csv_no_domain", "bedconv", "@good.csv @out.h5", 2, {"--domain"});
  add("bedconv_domain_for_h5", "bedconv", "@good.h5 @out.csv" + dom, 2, {"--domain", "only for CSV"});
  add("bedconv_domain_short", "bedconv", "@good.csv @out.h5 --domain 0,0,0,1", 2, {"--domain", "4 numbers"});
  add("bedconv_domain_inverted", "bedconv", "@good.csv @out.h5 --domain 1,0,0,0,1,1", 2, {"--domain", "lower < upper"});
  add("bedconv_csv_outside_domain", "bedconv", "@good.csv @out.h5 --domain 0,0,0,1e-5,1e-5,1e-5", 2,
      {"radius", "um"});
  add("bedconv_missing_out", "bedconv", "@good.h5", 2, {"out"});
  add("bedconv_ok_csv", "bedconv", "@good.h5 @new.csv", 0, {});
  add("bedconv_ok_data", "bedconv", "@good.h5 @new.data --density 7900", 0, {});
  add("bedconv_ok_dump", "bedconv", "@good.dump @new.h5", 0, {});
  // Foreign formats (docs/decks.md): a damaged file exits 2 naming file and line.
  add("bedconv_data_truncated", "bedconv", "@cut.data @out.h5", 2, {"@cut.data", "1 of the 2 atoms"});
  add("bedconv_yade_columns", "bedconv", "@bad_yade.txt @out.h5", 2, {"@bad_yade.txt:2:", "x y z r"});
  add("bedconv_geo_header", "bedconv", "@bad.geo @out.h5", 2, {"@bad.geo:1:", "LSMGeometry"});
  add("bedconv_gz_damaged", "bedconv", "@bad.dump.gz @out.h5", 2, {"@bad.dump.gz", "gzip"});
  add("bedconv_all_snapshots_h5", "bedconv", "@good.h5 @out.h5 --all-snapshots", 2, {"--all-snapshots"});
  add("bedconv_deck_not_data", "bedconv", "@good.h5 @out.csv --deck lammps", 2, {"--deck", ".data"});

  // packgen.
  add("packgen_ok", "packgen", pk_ok, 0, {});
  add("packgen_count_negative", "packgen", pk + "--seed 1 --count -5 --out @out.h5", 2, {"--count", "-5", "negative"});
  add("packgen_count_huge", "packgen", pk + "--seed 1 --count 1e11 --out @out.h5", 2, {"--count", "cannot fit"});
  add("packgen_count_huge_digits", "packgen", pk + "--seed 1 --count 100000000000 --out @out.h5", 2, {"--count"});
  add("packgen_count_zero", "packgen", pk + "--seed 1 --count 0 --out @out.h5", 2, {"--count", ">= 1"});
  add("packgen_count_fraction", "packgen", pk + "--seed 1 --count 2.5 --out @out.h5", 2, {"--count", "2.5"});
  add("packgen_count_word", "packgen", pk + "--seed 1 --count ten --out @out.h5", 2, {"--count", "ten"});
  add("packgen_count_ini", "packgen", pk + "--seed 1 --out @out.h5 --config @packgen_count.ini", 2,
      {"packgen_count.ini:3", "count", "-5"});
  add("packgen_seed_ini", "packgen", pk + "--out @out.h5 --config @seed_negative.ini", 2,
      {"seed_negative.ini:3", "seed", "-1"});
  add("packgen_dim_word", "packgen", "--dim three --domain 1e-4,1e-4,1e-4 --psd mono:d=2e-5 --seed 1 --out @out.h5", 2,
      {"--dim", "three", "2 or 3"});
  add("packgen_dim_4", "packgen", "--dim 4 --domain 1e-4,1e-4,1e-4 --psd mono:d=2e-5 --seed 1 --out @out.h5", 2,
      {"--dim", "2 or 3"});
  add("packgen_dim_mismatch", "packgen", "--dim 2 --domain 1e-4,1e-4,1e-4 --psd mono:d=2e-5 --seed 1 --out @out.h5", 2,
      {"--dim", "3 lengths"});
  add("packgen_domain_metres_for_um", "packgen", "--dim 3 --domain 200,200,100 --psd mono:d=2e-5 --seed 1 --out @out.h5", 2,
      {"--domain", "um", "--allow-huge"});
  add("packgen_domain_2d_slip", "packgen", "--dim 2 --domain 2000,1000 --psd mono:d=2e-5 --seed 1 --out @out.h5", 2,
      {"--domain", "um"});
  add("packgen_domain_one_length", "packgen", "--dim 3 --domain 1e-4 --psd mono:d=2e-5 --seed 1 --out @out.h5", 2,
      {"--domain", "2 to 3"});
  add("packgen_domain_negative", "packgen", "--dim 3 --domain -1e-4,1e-4,1e-4 --psd mono:d=2e-5 --seed 1 --out @out.h5", 2,
      {"--domain", "lower < upper"});
  add("packgen_domain_nan", "packgen", "--dim 3 --domain nan,1e-4,1e-4 --psd mono:d=2e-5 --seed 1 --out @out.h5", 2,
      {"--domain", "nan"});
  add("packgen_domain_smaller_than_particle", "packgen", "--dim 3 --domain 1e-5,1e-4,1e-4 --psd mono:d=2e-5 --seed 1 --out @out.h5", 2,
      {"--domain", "smallest particle"});
  add("packgen_psd_word", "packgen", "--dim 3 --domain 1e-4,1e-4,1e-4 --psd spheres --seed 1 --out @out.h5", 2, {"--psd"});
  add("packgen_psd_negative", "packgen", "--dim 3 --domain 1e-4,1e-4,1e-4 --psd mono:d=-2e-5 --seed 1 --out @out.h5", 2, {"--psd"});
  add("packgen_psd_table_missing", "packgen", "--dim 3 --domain 1e-4,1e-4,1e-4 --psd table:file=@nowhere.csv --seed 1 --out @out.h5", 2,
      {"nowhere.csv"});
  add("packgen_approach_5", "packgen", pk + "--seed 1 --approach 5 --out @out.h5", 2, {"--approach", "5"});
  add("packgen_approach_3_in_2d", "packgen", "--dim 2 --domain 1e-4,1e-4 --psd mono:d=2e-5 --approach 3 --seed 1 --out @out.h5", 2,
      {"--approach", "3D"});
  add("packgen_tries_0", "packgen", pk + "--seed 1 --tries 0 --out @out.h5", 2, {"--tries"});
  add("packgen_tries_negative", "packgen", pk + "--seed 1 --tries -3 --out @out.h5", 2, {"--tries"});
  add("packgen_directions_0", "packgen", pk + "--seed 1 --directions 0 --out @out.h5", 2, {"--directions"});
  add("packgen_retire_negative", "packgen", pk + "--seed 1 --retire-after -1 --out @out.h5", 2, {"--retire-after"});
  add("packgen_max_failures_0", "packgen", pk + "--seed 1 --max-failures 0 --out @out.h5", 2, {"--max-failures"});
  add("packgen_max_failures_negative", "packgen", pk + "--seed 1 --max-failures -1 --out @out.h5", 2, {"--max-failures", "negative"});
  add("packgen_target_density_big", "packgen", pk + "--seed 1 --target-density 1.5 --out @out.h5", 2, {"--target-density"});
  add("packgen_target_density_nan", "packgen", pk + "--seed 1 --target-density nan --out @out.h5", 2, {"--target-density", "nan"});
  add("packgen_two_stop_rules", "packgen", pk + "--seed 1 --count 5 --target-density 0.3 --out @out.h5", 2, {"--count", "--target-density"});
  add("packgen_edge_fraction", "packgen", pk + "--seed 1 --edge-fraction 2 --out @out.h5", 2, {"--edge-fraction"});
  add("packgen_floor_seed", "packgen", pk + "--seed 1 --floor-seed 1 --out @out.h5", 2, {"--floor-seed"});
  add("packgen_collision_word", "packgen", pk + "--seed 1 --collision octree --out @out.h5", 2, {"--collision", "octree"});
  add("packgen_raster_no_spacing", "packgen", pk + "--seed 1 --collision raster --out @out.h5", 2, {"--raster-spacing"});
  add("packgen_raster_negative", "packgen", pk + "--seed 1 --collision raster --raster-spacing -1e-6 --out @out.h5", 2, {"--raster-spacing"});
  add("packgen_raster_too_fine", "packgen", pk + "--seed 1 --collision raster --raster-spacing 1e-12 --out @out.h5", 2,
      {"--raster-spacing", "GiB"});
  add("packgen_site_order_word", "packgen", pk + "--seed 1 --site-order highest --out @out.h5", 2, {"--site-order"});
  add("packgen_size_sampling_word", "packgen", pk + "--seed 1 --size-sampling sobol --out @out.h5", 2, {"--size-sampling"});
  add("packgen_phases_word", "packgen", pk + "--seed 1 --phases a:b --out @out.h5", 2, {"--phases"});
  add("packgen_phases_density", "packgen", pk + "--seed 1 --phases 0:0.5,1:0.3 --out @out.h5", 2, {"--phases"});
  add("packgen_missing_seed", "packgen", pk + "--out @out.h5", 2, {"seed"});
  add("packgen_missing_out", "packgen", pk + "--seed 1", 2, {"out"});
  add("packgen_out_txt", "packgen", pk + "--seed 1 --out @out.txt", 2, {"--out", ".txt", ".h5"});
  add("packgen_out_csv", "packgen", pk + "--seed 1 --out @out.csv", 2, {"--out", ".csv", "bedconv"});
  add("packgen_out_no_folder", "packgen", pk + "--seed 1 --out @nowhere/out.h5", 2, {"--out", "nowhere", "does not exist"});
  add("packgen_out_folder", "packgen", pk + "--seed 1 --out @adir/", 2, {"--out", "adir"});
  add("packgen_out_sidecar_folder", "packgen", pk + "--seed 1 --out @side.h5", 2, {"--out", "side.xmf", "folder"});
  add("packgen_old_output_kept", "packgen", "--dim 3 --domain 1e-4,1e-4,1e-4 --psd mono:d=-1 --seed 1 --out @old.h5", 2, {"--psd"});

  // bedstat.
  add("bedstat_ok", "bedstat", "@good.h5 --json", 0, {});
  add("bedstat_tol_negative", "bedstat", "@good.h5 --tol -1", 2, {"--tol"});
  add("bedstat_tol_nan", "bedstat", "@good.h5 --tol nan", 2, {"--tol", "nan"});
  add("bedstat_tol_ini", "bedstat", "@good.h5 --config @nan_value.ini", 2, {"nan_value.ini:2", "tol", "nan"});
  add("bedstat_layer_inverted", "bedstat", "@good.h5 --layer 2e-5,1e-5", 2, {"--layer", "Z0 < Z1"});
  add("bedstat_layer_word", "bedstat", "@good.h5 --layer a,b", 2, {"--layer"});
  add("bedstat_layer_one", "bedstat", "@good.h5 --layer 1e-5", 2, {"--layer", "2"});
  add("bedstat_profile_negative", "bedstat", "@good.h5 --profile -1", 2, {"--profile", "negative"});
  add("bedstat_profile_huge", "bedstat", "@good.h5 --profile 1e14", 2, {"--profile", "0 to 1000000"});
  add("bedstat_rdf_negative", "bedstat", "@good.h5 --rdf -5", 2, {"--rdf", "-5"});
  add("bedstat_rdf_huge", "bedstat", "@good.h5 --rdf 1e9", 2, {"--rdf", "0 to 1000000"});
  add("bedstat_histogram_huge", "bedstat", "@good.h5 --histogram 100000000", 2, {"--histogram", "0 to 1000000"});
  add("bedstat_histogram_fraction", "bedstat", "@good.h5 --histogram 2.5", 2, {"--histogram", "2.5"});
  add("bedstat_voronoi_2d", "bedstat", "@good2d.h5 --voronoi", 2, {"--voronoi", "2D", "3D"});
  add("bedstat_order_2d", "bedstat", "@good2d.h5 --order", 2, {"--order", "2D"});
  add("bedstat_order_margin_negative", "bedstat", "@good.h5 --order --order-margin -1e-5", 2, {"--order-margin"});
  add("bedstat_psd_bad", "bedstat", "@good.h5 --psd gauss:mean=3e-5", 2, {"--psd"});
  add("bedstat_csv_no_domain", "bedstat", "@good.csv", 2, {"domain"});
  add("bedstat_csv_bad_domain", "bedstat", "@good.csv --domain 0,0,0,1,1", 2, {"--domain"});
  add("bedstat_unknown_extension", "bedstat", "@good.txt", 2, {"does not exist"});
  add("bedstat_second_bed_bad", "bedstat", "@good.h5 @um_radii.h5", 2, {"um_radii.h5", "um"});
  add("bedstat_spread_2d", "bedstat", "@good2d.h5 --spread --gap 1e-5", 2, {"--spread", "2D"});
  add("bedstat_spread_no_gap", "bedstat", "@good.h5 --spread", 2, {"--gap", "recoater.gap"});
  add("bedstat_spread_gap_nan", "bedstat", "@good.h5 --spread --gap nan", 2, {"--gap", "nan"});
  add("bedstat_spread_window_inverted", "bedstat", "@good.h5 --spread --gap 1e-5 --window 2e-5,1e-5", 2, {"--window", "X0 < X1"});
  add("bedstat_spread_raster_zero", "bedstat", "@good.h5 --spread --gap 1e-5 --raster 0", 2, {"--raster", "> 0"});
  add("bedstat_spread_bins_zero", "bedstat", "@good.h5 --spread --gap 1e-5 --segregation-bins 0", 2, {"--segregation-bins", "1 to 1000000"});
  add("bedstat_spread_feed_missing", "bedstat", "@good.h5 --spread --gap 1e-5 --feed @missing.h5", 2, {"--feed", "does not exist"});
  add("bedstat_spread_option_alone", "bedstat", "@good.h5 --window 0,1e-5", 2, {"--window", "--spread"});

  // deposit.
  const std::string dep = "--in @good.h5 --t-end 1e-5 --seed 1 ";
  add("deposit_count_negative", "deposit", "--psd mono:d=2e-5 --domain 1e-4,1e-4,1e-4 --count -5 --t-end 1e-5 --seed 1 --out @out.h5", 2,
      {"--count", "-5"});
  add("deposit_count_zero", "deposit", "--psd mono:d=2e-5 --domain 1e-4,1e-4,1e-4 --count 0 --t-end 1e-5 --seed 1 --out @out.h5", 2,
      {"--count", "0"});
  add("deposit_in_and_psd", "deposit", dep + "--psd mono:d=2e-5 --out @out.h5", 2, {"--in", "--psd"});
  add("deposit_no_source", "deposit", "--t-end 1e-5 --seed 1 --out @out.h5", 2, {"--in", "--psd"});
  add("deposit_every_negative", "deposit", dep + "--trajectory @traj.h5 --every -1 --out @out.h5", 2, {"--every", "-1"});
  add("deposit_every_zero", "deposit", dep + "--trajectory @traj.h5 --every 0 --out @out.h5", 2, {"--every"});
  add("deposit_dt_negative", "deposit", dep + "--dt -1e-9 --out @out.h5", 2, {"--dt"});
  add("deposit_dt_nan", "deposit", dep + "--dt nan --out @out.h5", 2, {"--dt", "nan"});
  add("deposit_t_end_missing", "deposit", "--in @good.h5 --seed 1 --out @out.h5", 2, {"--t-end"});
  add("deposit_integrator_word", "deposit", dep + "--integrator euler --out @out.h5", 2, {"euler"});
  add("deposit_periodic_word", "deposit", dep + "--periodic z --out @out.h5", 2, {"--periodic", "z"});
  add("deposit_contact_law_word", "deposit", dep + "--contact.law spring --out @out.h5", 2, {"spring"});
  add("deposit_stiffness_with_hertz", "deposit", dep + "--contact.stiffness 100 --out @out.h5", 2, {"contact.stiffness"});
  add("deposit_domain_2d", "deposit", "--psd mono:d=2e-5 --domain 1e-4,1e-4 --count 5 --t-end 1e-5 --seed 1 --out @out.h5", 2,
      {"--domain", "2D"});
  add("deposit_young_scale_negative", "deposit", dep + "--young-scale -1 --out @out.h5", 2, {"young"});
  add("deposit_out_no_folder", "deposit", dep + "--out @nowhere/out.h5", 2, {"--out", "nowhere"});
  add("deposit_out_is_in", "deposit", dep + "--out @good.h5", 2, {"--out", "input"});
  add("deposit_out_txt", "deposit", dep + "--out @out.txt", 2, {"--out", ".txt"});
  add("deposit_trajectory_no_folder", "deposit", dep + "--trajectory @nowhere/traj.h5 --every 10 --out @out.h5", 2,
      {"--trajectory", "nowhere"});
  add("deposit_material_young_gpa", "deposit", dep + "--material.young 193 --out @out.h5", 2, {"material.young", "193"});
  add("deposit_fines_scaling_word", "deposit", dep + "--fines.scaling volume --out @out.h5", 2,
      {"fines.scaling", "volume"});
  add("deposit_fines_radius_zero", "deposit", dep + "--fines.scaling mass --out @out.h5", 2,
      {"fines.radius", "0"});
  add("deposit_fines_radius_negative", "deposit",
      dep + "--fines.scaling stiffness --fines.radius -1e-6 --out @out.h5", 2, {"fines.radius", "-1e-06"});
  add("deposit_fines_stiffness_linear", "deposit",
      dep + "--contact.law linear --contact.stiffness 100 --fines.scaling stiffness --fines.radius 1e-5 --out @out.h5",
      2, {"fines.scaling", "linear"});
  add("deposit_rotating_rk4", "deposit", dep + "--friction.model history --integrator rk4 --out @out.h5", 2,
      {"friction.model", "rk4"});

  // keff.
  const std::string kf = "--bed @good.h5 ";
  add("keff_profile_bins_negative", "keff", kf + "--profile-bins -1 --out @out.h5", 2, {"--profile-bins", "-1"});
  add("keff_profile_bins_huge", "keff", kf + "--profile-bins 1e14 --out @out.h5", 2, {"--profile-bins"});
  add("keff_rays_negative", "keff", kf + "--rays -5 --out @out.h5", 2, {"--rays", "-5"});
  add("keff_axis_word", "keff", kf + "--axis w --out @out.h5", 2, {"--axis", "w"});
  add("keff_temperature_negative", "keff", kf + "--temperature -5 --out @out.h5", 2, {"--temperature"});
  add("keff_temperature_nan", "keff", kf + "--temperature nan --out @out.h5", 2, {"--temperature", "nan"});
  add("keff_gas_model_word", "keff", kf + "--gas.model helium --out @out.h5", 2, {"gas.model", "helium"});
  add("keff_radiation_model_word", "keff", kf + "--radiation.model mc --out @out.h5", 2, {"radiation.model", "mc"});
  add("keff_lens_region_word", "keff", kf + "--gas.lens-region all --out @out.h5", 2, {"gas.lens-region"});
  add("keff_contact_radius_word", "keff", kf + "--contact.radius elastic --out @out.h5", 2, {"contact.radius", "elastic"});
  add("keff_missing_bed", "keff", "--out @out.h5", 2, {"--bed"});
  add("keff_bed_missing_file", "keff", "--bed @missing.h5 --out @out.h5", 2, {"missing.h5"});
  add("keff_out_no_folder", "keff", kf + "--out @nowhere/out.h5", 2, {"--out", "nowhere"});
  add("keff_out_is_bed", "keff", kf + "--out @good.h5", 2, {"--out", "input"});
  add("keff_profile_folder", "keff", kf + "--profile-bins 4 --out @prof.h5", 2, {"prof-profile.csv", "folder"});
  add("keff_min_gap_metre", "keff", kf + "--gas.min-gap 1 --out @out.h5", 2, {"gas.min-gap"});

  // sinter.
  const std::string si = sinter + "--bed @wide.h5 ";  // wider than the scene's spot
  add("sinter_snapshots_negative", "sinter", si + "--snapshots -1 --out @out.h5", 2, {"--snapshots", "-1"});
  add("sinter_rays_negative", "sinter", si + "--laser.rays -5 --out @out.h5", 2, {"--laser.rays", "-5"});
  add("sinter_power_nan", "sinter", si + "--power nan --out @out.h5", 2, {"--power", "nan"});
  add("sinter_speed_inf", "sinter", si + "--speed inf --out @out.h5", 2, {"--speed", "inf"});
  add("sinter_integrator_word", "sinter", si + "--integrator rk4 --out @out.h5", 2, {"--integrator", "rk4"});
  add("sinter_grid_spacing_negative", "sinter", si + "--grid-spacing -1e-6 --out @out.h5", 2, {"--grid-spacing"});
  add("sinter_dt_negative", "sinter", si + "--dt -1 --out @out.h5", 2, {"--dt"});
  add("sinter_absorption_word", "sinter", si + "--laser.absorption magic --out @out.h5", 2, {"laser.absorption", "magic"});
  add("sinter_reflection_word", "sinter", si + "--laser.reflection mirror --out @out.h5", 2, {"laser.reflection"});
  add("sinter_substrate_nodes_word", "sinter", si + "--substrate.nodes a,b,c --out @out.h5", 2, {"substrate.nodes"});
  add("sinter_substrate_nodes_huge", "sinter", si + "--substrate.nodes 100000,100000,100000 --out @out.h5", 2,
      {"substrate.nodes"});
  add("sinter_substrate_periodic_word", "sinter", si + "--substrate.periodic x --out @out.h5", 2,
      {"substrate.periodic", "'x'", "none, y"});
  add("sinter_substrate_periodic_bounded_bed", "sinter", si + "--substrate.periodic y --out @out.h5", 2,
      {"substrate.periodic", "bounded along y"});
  add("sinter_missing_out", "sinter", si, 2, {"--out"});
  add("sinter_spot_metres", "sinter", si + "--spot 54 --out @out.h5", 2, {"--spot", "54"});
  add("sinter_out_is_bed", "sinter", si + "--out @wide.h5", 2, {"--out", "input"});
  add("sinter_out_no_folder", "sinter", si + "--out @nowhere/out.h5", 2, {"--out", "nowhere"});
  add("sinter_out_txt", "sinter", si + "--out @out.txt", 2, {"--out", ".txt"});
  add("sinter_substrate_depth_metres", "sinter", si + "--substrate.depth 0.3 --out @out.h5", 2, {"substrate.depth"});
  add("sinter_hatch_zero", "sinter", si + "--scan.hatch 0 --out @out.h5", 2, {"scan.hatch"});
  add("sinter_scan_path_missing", "sinter", si + "--scan-path @nowhere.csv --out @out.h5", 2,
      {"--scan-path"});
  add("sinter_fused_bed_is_bed", "sinter", si + "--fuse --fused-bed @wide.h5 --out @out.h5", 2,
      {"--fused-bed", "input"});
  return t;
}

// ----------------------------------------------------------------------------------------------
// Running one case.

std::map<std::string, std::string> snapshot(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string rel = fs::relative(e.path(), dir).string();
    // A FIFO or a link to a device is recorded by kind: reading it would block or never end.
    files[rel] = e.is_directory()      ? std::string("<folder>")
                 : e.is_regular_file() ? powderbed::test::read_text(e.path().string())
                                       : std::string("<special>");
  }
  return files;
}

// "@name" -> dir/name (making the file), "{scenes}" -> the source's data/scenes.
std::string expand(const std::string& text, const std::string& dir, bool make) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '@') {
      std::size_t j = i + 1;
      while (j < text.size() && text[j] != ' ') ++j;
      const std::string name = text.substr(i + 1, j - i - 1);
      const std::string first = name.substr(0, name.find('/'));
      if (make && !first.empty()) {
        make_file(dir, first);  // names without a recipe (out.h5, missing.h5) stay absent
        if (first == "side.h5") make_file(dir, "side.xmf");          // the sidecar is a folder
        if (first == "prof.h5") make_file(dir, "prof-profile.csv");  // keff's profile is a folder
      }
      out += dir + "/" + name;
      i = j - 1;
    } else if (text.compare(i, 8, "{scenes}") == 0) {
      out += std::string(POWDERBED_SOURCE_DIR) + "/data/scenes";
      i += 7;
    } else if (text.compare(i, 10, "{testdata}") == 0) {
      out += POWDERBED_TEST_DATA;
      i += 9;
    } else {
      out += text[i];
    }
  }
  return out;
}

class Hardening : public ::testing::TestWithParam<Case> {};

TEST_P(Hardening, RefusedCleanly) {
  const Case& c = GetParam();
  const std::string dir = powderbed::test::scratch_dir("hard_" + c.name);
  const std::string args = expand(c.args, dir, true);
  const auto before = snapshot(dir);
  // A reader that hangs (on a FIFO, say) fails its case after a minute instead of the suite.
  const CommandResult r = powderbed::test::run_app(c.app, args, 60);
  EXPECT_EQ(r.status, c.status) << c.app << " " << args << "\n" << r.err;
  if (c.status != 0) {
    EXPECT_EQ(r.err_lines(), 1) << "one line on stderr, got:\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << "stdout: " << r.out;
    for (const auto& w : c.words) {
      const std::string word = expand(w, dir, false);
      EXPECT_NE(r.err.find(word), std::string::npos) << "'" << word << "' not in: " << r.err;
    }
    // Nothing written, nothing destroyed: the folder is byte for byte what it was.
    const auto after = snapshot(dir);
    for (const auto& [name, content] : before) {
      const auto it = after.find(name);
      EXPECT_TRUE(it != after.end()) << name << " was removed";
      if (it != after.end()) {
        EXPECT_TRUE(it->second == content) << name << " was changed";
      }
    }
    for (const auto& [name, content] : after)
      EXPECT_TRUE(before.count(name)) << name << " was written by a refused run";
  }
  fs::remove_all(dir);
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Table, Hardening, ::testing::ValuesIn(all_cases()), case_name);

TEST(HardeningTable, HasAtLeast550CasesWithUniqueNames) {
  const auto t = all_cases();
  EXPECT_GE(t.size(), 550u);
  std::map<std::string, int> seen;
  for (const auto& c : t) EXPECT_EQ(++seen[c.name], 1) << c.name;
}

// ----------------------------------------------------------------------------------------------
// Kill tests: a program killed while it works or writes leaves the old output as it was and no
// temporary (SIGINT/SIGTERM: removed by the handler; SIGKILL: by the next writer of that path).

pid_t spawn(const std::string& app, const std::vector<std::string>& args) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<std::string> all = {std::string(POWDERBED_APPS_DIR) + "/" + app};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    ::execv(argv[0], argv.data());
    std::_Exit(127);
  }
  return pid;
}

std::vector<std::string> temporaries(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.find(".tmp") != std::string::npos) out.push_back(n);
  }
  return out;
}

// packgen of ~40k spheres: long enough (about a second or more) to be killed while it packs or
// writes; the delays walk through the run.
void kill_packgen_and_check(int sig) {
  const std::string dir = powderbed::test::scratch_dir(std::string("hard_kill_") + (sig == SIGKILL ? "9" : "2"));
  const std::string out = dir + "/out.h5";
  powderbed::bed::write_bed_h5(good_bed(), out);
  const std::string old_h5 = powderbed::test::read_text(out);
  const std::string old_xmf = powderbed::test::read_text(dir + "/out.xmf");
  const std::vector<std::string> args = {"--dim", "3", "--domain", "1e-3,1e-3,5e-4", "--psd",
                                         "mono:d=2e-5", "--approach", "3", "--seed", "1",
                                         "--out", out};
  int killed = 0;
  for (int delay_ms : {50, 150, 300, 600, 1000}) {
    const pid_t pid = spawn("packgen", args);
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    const bool running = ::kill(pid, sig) == 0;
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (running && WIFSIGNALED(status)) ++killed;
    // The output is the old bed or a whole new one, never a part.
    const std::string now = powderbed::test::read_text(out);
    if (now != old_h5) {
      EXPECT_NO_THROW(powderbed::bed::read_bed_h5(out)) << "after a kill at " << delay_ms << " ms";
    } else {
      EXPECT_EQ(powderbed::test::read_text(dir + "/out.xmf"), old_xmf);
    }
    if (sig != SIGKILL) {
      EXPECT_TRUE(temporaries(dir).empty()) << "left " << temporaries(dir).front();
    }
  }
  EXPECT_GE(killed, 1) << "no run was still going when the signal came: lengthen the run";
  // Mid-write: bedconv of 64 000 spheres to CSV holds its temporary while it formats the text
  // (tens of ms); poll for the temporary and signal the moment it appears.
  const std::string big = dir + "/big.h5", csv = dir + "/out.csv";
  powderbed::bed::write_bed_h5(powderbed::bed::simple_cubic_lattice(40, 1e-6), big);
  powderbed::bed::write_bed_csv(good_bed(), csv);
  const std::string old_csv = powderbed::test::read_text(csv);
  int mid_write = 0;
  for (int attempt = 0; attempt < 10 && mid_write < 2; ++attempt) {
    const pid_t pid = spawn("bedconv", {big, csv});
    bool seen = false;
    int status = 0;
    while (!seen && ::waitpid(pid, &status, WNOHANG) == 0) {
      seen = !temporaries(dir).empty();
      if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    if (seen) {
      ::kill(pid, sig);
      ::waitpid(pid, &status, 0);
      if (WIFSIGNALED(status)) ++mid_write;
    }
    const std::string now = powderbed::test::read_text(csv);
    if (now != old_csv) {  // a whole new file: the header and all 64 000 rows
      EXPECT_EQ(std::count(now.begin(), now.end(), '\n'), 64001) << "a partial CSV after a kill";
    }
    if (sig != SIGKILL) {
      EXPECT_TRUE(temporaries(dir).empty()) << "left " << temporaries(dir).front();
    }
  }
  EXPECT_GE(mid_write, 1) << "never caught bedconv while its temporary existed";
  if (sig == SIGKILL) {
    // Whatever a SIGKILLed run left is removed by the next writer of the same path.
    const CommandResult r = powderbed::test::run_app(
        "packgen", "--dim 3 --domain 1e-4,1e-4,1e-4 --psd mono:d=2e-5 --seed 1 --out " + out);
    EXPECT_EQ(r.status, 0) << r.err;
    const CommandResult c = powderbed::test::run_app("bedconv", big + " " + csv);
    EXPECT_EQ(c.status, 0) << c.err;
    EXPECT_TRUE(temporaries(dir).empty()) << "left " << temporaries(dir).front();
  }
  fs::remove_all(dir);
}

TEST(HardeningKill, SigintLeavesOldOutputAndNoTemporaries) { kill_packgen_and_check(SIGINT); }
TEST(HardeningKill, SigtermLeavesOldOutputAndNoTemporaries) { kill_packgen_and_check(SIGTERM); }
TEST(HardeningKill, SigkillLeavesOldOutputAndTheNextRunCleansUp) { kill_packgen_and_check(SIGKILL); }

// deposit's trajectory: SIGINT during a run removes out.h5's and traj.h5's temporaries.
TEST(HardeningKill, SigintDuringDepositTrajectoryLeavesNoTemporaries) {
  const std::string dir = powderbed::test::scratch_dir("hard_kill_deposit");
  const std::string out = dir + "/out.h5";
  powderbed::bed::write_bed_h5(good_bed(), out);
  const std::string old_h5 = powderbed::test::read_text(out);
  const pid_t pid = spawn("deposit", {"--psd", "mono:d=2e-5", "--domain", "4e-4,4e-4,4e-4",
                                      "--count", "400", "--t-end", "10", "--seed", "1",
                                      "--threads", "1", "--trajectory", dir + "/traj.h5",
                                      "--every", "50", "--out", out});
  bool saw_temporary = false;
  for (int i = 0; i < 100 && !saw_temporary; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    saw_temporary = !temporaries(dir).empty();
  }
  EXPECT_TRUE(saw_temporary) << "the trajectory's temporary never appeared";
  for (const auto& n : temporaries(dir)) EXPECT_NE(n.find(std::to_string(pid)), std::string::npos) << n;
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT);
  EXPECT_TRUE(temporaries(dir).empty()) << "left " << temporaries(dir).front();
  EXPECT_EQ(powderbed::test::read_text(out), old_h5);
  fs::remove_all(dir);
}

}  // namespace

// A bed written before the floor's contacts had slots (42 wall values a particle: 7 walls x 6)
// still continues: its walls' histories read back unchanged and its floor slots free.
TEST(HardeningRestart, WallHistoryOfTheEarlierLayoutReadsWithTheFloorSlotsFree) {
  namespace dem = powderbed::dem;
  powderbed::bed::Bed bed;
  bed.domain.dimension = 3;
  bed.domain.upper = {1e-3, 1e-3, 1e-3};
  bed.add(2e-4, 2e-4, 1e-4, 2e-5);
  bed.add(6e-4, 2e-4, 1e-4, 2e-5);
  bed.vx.assign(2, 0.0);
  bed.vy.assign(2, 0.0);
  bed.vz.assign(2, 0.0);
  dem::SpreadState state;
  state.dt = 1e-8;
  state.wx = state.wy = state.wz = {0.0, 0.0};
  state.wall_history.assign(2 * dem::kWallHistoryValues, 0.0);
  std::vector<double> earlier;
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t v = 0; v < 42; ++v) {
      state.wall_history[i * dem::kWallHistoryValues + v] = 1.0 + static_cast<double>(100 * i + v);
      earlier.push_back(1.0 + static_cast<double>(100 * i + v));
    }
  const std::string path = (fs::temp_directory_path() / ("earlier-walls-" + std::to_string(getpid()) + ".h5")).string();
  dem::write_spread_bed(path, bed, state);
  H5(path).doubles("/restart/wall_history", earlier, 42);
  const dem::SpreadState read = dem::read_spread_state(path, bed);
  fs::remove(path);
  fs::remove(path.substr(0, path.size() - 3) + ".xmf");
  EXPECT_EQ(read.wall_history, state.wall_history);
}
