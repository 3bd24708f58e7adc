// The /restart group of a bed written at a layer's end (spread.hpp SpreadState;
// docs/deposit-spread.md "Restarts"): attributes for the scalars, datasets for the per-particle
// and per-contact state, all float64 or uint64 so that a continued run reads back every bit.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <unordered_set>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_input.hpp"
#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::dem {

namespace {

constexpr const char* kGroup = "/restart";
constexpr std::size_t kWallValues = kWallHistoryValues;  // spread.hpp SpreadState::wall_history
constexpr std::size_t kWallsOnly = 42;  // before the floor's contacts: 7 walls x (F_s, M_r)

void fail(const std::string& path, const std::string& what) {
  throw InputError(path + ": /restart: " + what);
}

std::string in_group(const char* name) { return std::string(kGroup) + "/" + name; }

// `data` as rows of `cols` values.
template <class T>
void write_rows(bed::H5Output& out, const char* name, const std::vector<T>& data, std::size_t cols,
                const std::string& units) {
  out.write(in_group(name), data, {data.size() / cols, cols}, units);
}

// The /restart group, added to the bed's temporary `temp` (named `path` in messages).
void write_state(const std::string& temp, const std::string& path, const SpreadState& s,
                 const bed::Bed& bed, const std::function<void(bed::H5Output&)>& more) {
  bed::H5Output out(temp, bed::H5Output::Mode::append, path);
  out.attribute(kGroup, "layers_done", s.layers_done);
  out.attribute(kGroup, "step", s.step);
  out.attribute(kGroup, "dt", s.dt);
  out.attribute(kGroup, "time", s.time);
  out.attribute(kGroup, "tool_x", s.tool_x);
  out.attribute(kGroup, "plate_offset", s.plate_offset);
  std::vector<double> omega(3 * bed.n());
  for (std::size_t i = 0; i < bed.n(); ++i) {
    omega[3 * i] = s.wx[i];
    omega[3 * i + 1] = s.wy[i];
    omega[3 * i + 2] = s.wz[i];
  }
  write_rows(out, "angular_velocity", omega, 3, "rad/s");
  write_rows(out, "pair_ids", s.pair_ids, 2, "1");
  write_rows(out, "pair_history", s.pair_history, 6, "N (F_s), N m (M_k)");
  write_rows(out, "wall_history", s.wall_history, kWallValues, "N (F_s), N m (M_k)");
  if (!s.floor.empty()) {
    const bed::HeightMap& f = s.floor;  // the solid under the powder: heights per node, x fastest
    out.attribute(kGroup, "floor_nx", static_cast<std::uint64_t>(f.nx));
    out.attribute(kGroup, "floor_ny", static_cast<std::uint64_t>(f.ny));
    out.attribute(kGroup, "floor_x0", f.x0);
    out.attribute(kGroup, "floor_y0", f.y0);
    out.attribute(kGroup, "floor_dx", f.dx);
    out.attribute(kGroup, "floor_dy", f.dy);
    write_rows(out, "floor", f.z, 1, "m");
  }
  if (more) more(out);
  out.commit();
}

// wall_history, from a bed written before the floor had its contacts too (kWallsOnly values a
// particle) with those contacts free: a spread continued from it starts them afresh.
std::vector<double> read_wall_history(const bed::H5Input& in) {
  const std::string name = in_group("wall_history");
  try {
    return in.read_doubles(name, kWallValues);
  } catch (const InputError&) {
    // Not of kWallValues columns: try the earlier layout, whose own error names what is wrong.
  }
  const std::vector<double> walls = in.read_doubles(name, kWallsOnly);
  std::vector<double> all((walls.size() / kWallsOnly) * kWallValues, 0.0);
  for (std::size_t i = 0; i < walls.size() / kWallsOnly; ++i)
    std::copy_n(walls.begin() + static_cast<std::ptrdiff_t>(i * kWallsOnly), kWallsOnly,
                all.begin() + static_cast<std::ptrdiff_t>(i * kWallValues));
  return all;
}

}  // namespace

void write_spread_bed(const std::string& path, const bed::Bed& bed, const SpreadState& state,
                      const std::function<void(bed::H5Output&)>& more) {
  bed::write_bed_h5(bed, path,
                    [&](const std::string& temp) { write_state(temp, path, state, bed, more); });
}

bool has_spread_state(const std::string& path) {
  try {
    return bed::H5Input(path).exists(kGroup);
  } catch (const InputError&) {
    return false;  // not an HDF5 file: a bed in another format, which has no /restart
  }
}

SpreadState read_spread_state(const std::string& path, const bed::Bed& bed) {
  const bed::H5Input in(path);
  if (!in.exists(kGroup))
    fail(path, "missing (accepted: a bed written at a layer's end by a spreading run)");
  const auto whole = [&](const char* name) { return in.uint64_attribute(kGroup, name); };
  const auto real = [&](const char* name) { return in.double_attribute(kGroup, name); };
  SpreadState s;
  s.layers_done = whole("layers_done");
  s.step = whole("step");
  s.dt = real("dt");
  s.time = real("time");
  s.tool_x = real("tool_x");
  s.plate_offset = real("plate_offset");
  const auto omega = in.read_doubles(in_group("angular_velocity"), 3);
  s.pair_ids = in.read_uint64s(in_group("pair_ids"), 2);
  s.pair_history = in.read_doubles(in_group("pair_history"), 6);
  s.wall_history = read_wall_history(in);
  if (!(s.dt > 0) || !std::isfinite(s.dt))
    fail(path, fmt::format("dt is {} (accepted: the time step of the run that wrote it, > 0 s)", s.dt));
  if (!std::isfinite(s.time) || !std::isfinite(s.tool_x) || !std::isfinite(s.plate_offset))
    fail(path, "time, tool_x or plate_offset is not finite (accepted: finite numbers)");
  if (omega.size() != 3 * bed.n() || s.wall_history.size() != kWallValues * bed.n() ||
      s.pair_history.size() != 3 * s.pair_ids.size()) {
    fail(path, "sizes do not match the bed's " + std::to_string(bed.n()) + " particles");
  }
  for (std::size_t i = 0; i < bed.n(); ++i) {
    s.wx.push_back(omega[3 * i]);
    s.wy.push_back(omega[3 * i + 1]);
    s.wz.push_back(omega[3 * i + 2]);
  }
  if (in.exists(in_group("floor"))) {
    bed::HeightMap& f = s.floor;
    f.nx = whole("floor_nx");
    f.ny = whole("floor_ny");
    f.x0 = real("floor_x0");
    f.y0 = real("floor_y0");
    f.dx = real("floor_dx");
    f.dy = real("floor_dy");
    f.z = in.read_doubles(in_group("floor"), 1);
    if (f.z.size() != f.nx * f.ny) {
      fail(path, fmt::format("floor has {} heights for {} x {} nodes", f.z.size(), f.nx, f.ny));
    }
  }
  const std::unordered_set<std::uint64_t> ids(bed.id.begin(), bed.id.end());
  for (const std::uint64_t id : s.pair_ids) {
    if (ids.count(id) == 0)
      fail(path, "pair_ids names particle id " + std::to_string(id) + ", which the bed lacks");
  }
  return s;
}

}  // namespace powderbed::dem
