// LAMMPS data file export, atom_style sphere (docs/bed-format.md: beds convert to LAMMPS
// and LIGGGHTS so a study can outgrow one machine).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

namespace {

// LAMMPS drops atoms outside the box of a fixed (f) boundary, so an axis with a centre on or
// beyond a face is widened to hold every centre, padded by 1e-9 of its length (far below any
// contact overlap). An axis with every centre strictly inside keeps its exact bounds, so a
// periodic box keeps its period.
std::array<double, 2> box_bounds(double lo, double hi, const std::vector<double>& c,
                                 bool& widened) {
  if (c.empty()) return {lo, hi};
  const auto [min_it, max_it] = std::minmax_element(c.begin(), c.end());
  if (*min_it > lo && *max_it < hi) return {lo, hi};
  widened = true;
  const double new_lo = std::min(lo, *min_it);
  const double new_hi = std::max(hi, *max_it);
  const double pad = 1e-9 * (new_hi - new_lo);
  return {new_lo - pad, new_hi + pad};
}

}  // namespace

void write_lammps_data(const Bed& bed, const std::string& path, double density) {
  bed.validate(path);
  if (!std::isfinite(density) || !(density > 0)) {
    std::ostringstream msg;
    msg << path << ": density is " << density << " (accepted: > 0 kg/m^3)";
    throw InputError(msg.str());
  }
  // LAMMPS ids start at 1 and are 32-bit in the default (smallbig) build.
  constexpr std::uint64_t max_id = std::numeric_limits<std::int32_t>::max() - 1;
  for (std::uint64_t id : bed.id) {
    if (id > max_id) {
      throw InputError(path + ": id " + std::to_string(id) + " does not fit a LAMMPS atom id " +
                       "(accepted: ids up to " + std::to_string(max_id) + ")");
    }
  }
  const Domain& d = bed.domain;
  bool widened = false;
  const auto bx = box_bounds(d.lower[0], d.upper[0], bed.x, widened);
  const auto by = box_bounds(d.lower[1], d.upper[1], bed.y, widened);
  std::array<double, 2> bz{};
  if (d.dimension == 3) {
    bz = box_bounds(d.lower[2], d.upper[2], bed.z, widened);
  } else {
    // A 2D bed becomes a thin slab around z = 0, one largest radius thick on each side.
    const double r_max =
        bed.n() ? *std::max_element(bed.radius.begin(), bed.radius.end()) : 1e-3 * d.length(0);
    bz = {-r_max, r_max};
  }

  std::string text;
  text.reserve(256 + bed.n() * 5 * 25);
  char line[256];
  auto append = [&](int len) { text.append(line, static_cast<std::size_t>(len)); };
  text += "LAMMPS data file, atom_style sphere, from powderbed";
  if (!bed.provenance.created_by.empty()) text += " (" + bed.provenance.created_by + ")";
  text += "\n\n# LAMMPS atom id = powderbed id + 1; one atom type; density in kg/m^3 (SI units)\n";
  if (d.dimension == 2) {
    text += "# 2D bed: disks in the z = 0 plane, given a z slab of +-r_max; use 'dimension 2' "
            "(density is then mass/area)\n";
  }
  if (widened) text += "# box widened past the bed domain to hold every particle centre\n";
  append(std::snprintf(line, sizeof line, "%zu atoms\n1 atom types\n\n", bed.n()));
  append(std::snprintf(line, sizeof line, "%.17g %.17g xlo xhi\n", bx[0], bx[1]));
  append(std::snprintf(line, sizeof line, "%.17g %.17g ylo yhi\n", by[0], by[1]));
  append(std::snprintf(line, sizeof line, "%.17g %.17g zlo zhi\n", bz[0], bz[1]));
  text += "\nAtoms # sphere\n\n";
  for (std::size_t i = 0; i < bed.n(); ++i) {
    append(std::snprintf(line, sizeof line, "%llu 1 %.17g %.17g %.17g %.17g %.17g\n",
                         static_cast<unsigned long long>(bed.id[i] + 1), 2.0 * bed.radius[i],
                         density, bed.x[i], bed.y[i], bed.z[i]));
  }
  detail::AtomicFile file(path);
  detail::write_text(file.temp_path(), path, text);
  file.commit();
}

}  // namespace powderbed::bed
