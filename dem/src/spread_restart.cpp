// The /restart group of a bed written at a layer's end (spread.hpp SpreadState;
// docs/deposit-spread.md "Restarts"): attributes for the scalars, datasets for the per-particle
// and per-contact state, all float64 or uint64 so that a continued run reads back every bit.
#include <hdf5.h>

#include <string>
#include <unordered_set>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_handle.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::dem {

namespace {

using bed::H5Attr;
using bed::H5Dataset;
using bed::H5File;
using bed::H5Group;
using bed::H5Space;

constexpr const char* kGroup = "restart";
constexpr std::size_t kWallValues = 42;  // 7 walls x (F_s, M_r)

void fail(const std::string& path, const std::string& what) {
  throw InputError(path + ": /restart: " + what);
}

template <class T>
void write_set(hid_t group, const char* name, hid_t type, const std::vector<T>& data,
               std::size_t cols, const std::string& path) {
  const hsize_t dims[2] = {static_cast<hsize_t>(data.size() / cols), static_cast<hsize_t>(cols)};
  H5Space space(H5Screate_simple(2, dims, nullptr));
  H5Dataset set(H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  if (!set.valid() || (!data.empty() && H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0))
    fail(path, std::string("cannot write ") + name);
}

template <class T>
std::vector<T> read_set(hid_t group, const char* name, hid_t type, std::size_t cols,
                        const std::string& path) {
  H5Dataset set(H5Dopen2(group, name, H5P_DEFAULT));
  if (!set.valid()) fail(path, std::string(name) + " is missing");
  H5Space space(H5Dget_space(set));
  hsize_t dims[2] = {0, 0};
  if (H5Sget_simple_extent_ndims(space) != 2 || H5Sget_simple_extent_dims(space, dims, nullptr) < 0 ||
      dims[1] != cols) {
    fail(path, std::string(name) + " is not an N x " + std::to_string(cols) + " array");
  }
  std::vector<T> data(static_cast<std::size_t>(dims[0] * dims[1]));
  if (!data.empty() && H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    fail(path, std::string("cannot read ") + name);
  return data;
}

template <class T>
void write_attribute(hid_t group, const char* name, hid_t type, T value, const std::string& path) {
  H5Space space(H5Screate(H5S_SCALAR));
  H5Attr attr(H5Acreate2(group, name, type, space, H5P_DEFAULT, H5P_DEFAULT));
  if (!attr.valid() || H5Awrite(attr, type, &value) < 0) fail(path, std::string("cannot write ") + name);
}

template <class T>
T read_attribute(hid_t group, const char* name, hid_t type, const std::string& path) {
  H5Attr attr(H5Aopen(group, name, H5P_DEFAULT));
  T value{};
  if (!attr.valid() || H5Aread(attr, type, &value) < 0) fail(path, std::string(name) + " is missing");
  return value;
}

}  // namespace

void write_spread_state(const std::string& path, const SpreadState& s, const bed::Bed& bed) {
  bed::silence_hdf5_errors();
  H5File file(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  if (!file.valid()) fail(path, "cannot open the bed file to add the group");
  H5Group group(H5Gcreate2(file, kGroup, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  if (!group.valid()) fail(path, "cannot create the group");
  write_attribute(group, "layers_done", H5T_NATIVE_UINT64, s.layers_done, path);
  write_attribute(group, "step", H5T_NATIVE_UINT64, s.step, path);
  write_attribute(group, "dt", H5T_NATIVE_DOUBLE, s.dt, path);
  write_attribute(group, "time", H5T_NATIVE_DOUBLE, s.time, path);
  write_attribute(group, "tool_x", H5T_NATIVE_DOUBLE, s.tool_x, path);
  write_attribute(group, "plate_offset", H5T_NATIVE_DOUBLE, s.plate_offset, path);
  std::vector<double> omega(3 * bed.n());
  for (std::size_t i = 0; i < bed.n(); ++i) {
    omega[3 * i] = s.wx[i];
    omega[3 * i + 1] = s.wy[i];
    omega[3 * i + 2] = s.wz[i];
  }
  write_set(group, "angular_velocity", H5T_NATIVE_DOUBLE, omega, 3, path);
  write_set(group, "pair_ids", H5T_NATIVE_UINT64, s.pair_ids, 2, path);
  write_set(group, "pair_history", H5T_NATIVE_DOUBLE, s.pair_history, 6, path);
  write_set(group, "wall_history", H5T_NATIVE_DOUBLE, s.wall_history, kWallValues, path);
  if (s.floor.empty()) return;
  const bed::HeightMap& f = s.floor;  // the solid under the powder: heights per node, x fastest
  write_attribute(group, "floor_nx", H5T_NATIVE_UINT64, static_cast<std::uint64_t>(f.nx), path);
  write_attribute(group, "floor_ny", H5T_NATIVE_UINT64, static_cast<std::uint64_t>(f.ny), path);
  write_attribute(group, "floor_x0", H5T_NATIVE_DOUBLE, f.x0, path);
  write_attribute(group, "floor_y0", H5T_NATIVE_DOUBLE, f.y0, path);
  write_attribute(group, "floor_dx", H5T_NATIVE_DOUBLE, f.dx, path);
  write_attribute(group, "floor_dy", H5T_NATIVE_DOUBLE, f.dy, path);
  write_set(group, "floor", H5T_NATIVE_DOUBLE, f.z, 1, path);
}

bool has_spread_state(const std::string& path) {
  bed::silence_hdf5_errors();
  H5File file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  return file.valid() && H5Lexists(file, kGroup, H5P_DEFAULT) > 0;
}

SpreadState read_spread_state(const std::string& path, const bed::Bed& bed) {
  bed::silence_hdf5_errors();
  H5File file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!file.valid()) fail(path, "cannot open the file");
  H5Group group(H5Gopen2(file, kGroup, H5P_DEFAULT));
  if (!group.valid()) fail(path, "missing (accepted: a bed written at a layer's end by a spreading run)");
  SpreadState s;
  s.layers_done = read_attribute<std::uint64_t>(group, "layers_done", H5T_NATIVE_UINT64, path);
  s.step = read_attribute<std::uint64_t>(group, "step", H5T_NATIVE_UINT64, path);
  s.dt = read_attribute<double>(group, "dt", H5T_NATIVE_DOUBLE, path);
  s.time = read_attribute<double>(group, "time", H5T_NATIVE_DOUBLE, path);
  s.tool_x = read_attribute<double>(group, "tool_x", H5T_NATIVE_DOUBLE, path);
  s.plate_offset = read_attribute<double>(group, "plate_offset", H5T_NATIVE_DOUBLE, path);
  const auto omega = read_set<double>(group, "angular_velocity", H5T_NATIVE_DOUBLE, 3, path);
  s.pair_ids = read_set<std::uint64_t>(group, "pair_ids", H5T_NATIVE_UINT64, 2, path);
  s.pair_history = read_set<double>(group, "pair_history", H5T_NATIVE_DOUBLE, 6, path);
  s.wall_history = read_set<double>(group, "wall_history", H5T_NATIVE_DOUBLE, kWallValues, path);
  if (omega.size() != 3 * bed.n() || s.wall_history.size() != kWallValues * bed.n() ||
      s.pair_history.size() != 3 * s.pair_ids.size() || !(s.dt > 0)) {
    fail(path, "sizes do not match the bed's " + std::to_string(bed.n()) + " particles");
  }
  for (std::size_t i = 0; i < bed.n(); ++i) {
    s.wx.push_back(omega[3 * i]);
    s.wy.push_back(omega[3 * i + 1]);
    s.wz.push_back(omega[3 * i + 2]);
  }
  if (H5Lexists(group, "floor", H5P_DEFAULT) > 0) {
    bed::HeightMap& f = s.floor;
    f.nx = read_attribute<std::uint64_t>(group, "floor_nx", H5T_NATIVE_UINT64, path);
    f.ny = read_attribute<std::uint64_t>(group, "floor_ny", H5T_NATIVE_UINT64, path);
    f.x0 = read_attribute<double>(group, "floor_x0", H5T_NATIVE_DOUBLE, path);
    f.y0 = read_attribute<double>(group, "floor_y0", H5T_NATIVE_DOUBLE, path);
    f.dx = read_attribute<double>(group, "floor_dx", H5T_NATIVE_DOUBLE, path);
    f.dy = read_attribute<double>(group, "floor_dy", H5T_NATIVE_DOUBLE, path);
    f.z = read_set<double>(group, "floor", H5T_NATIVE_DOUBLE, 1, path);
    if (f.z.size() != f.nx * f.ny) fail(path, "floor has " + std::to_string(f.z.size()) +
                                              " heights for " + std::to_string(f.nx) + " x " +
                                              std::to_string(f.ny) + " nodes");
  }
  const std::unordered_set<std::uint64_t> ids(bed.id.begin(), bed.id.end());
  for (const std::uint64_t id : s.pair_ids) {
    if (ids.count(id) == 0)
      fail(path, "pair_ids names particle id " + std::to_string(id) + ", which the bed lacks");
  }
  return s;
}

}  // namespace powderbed::dem
