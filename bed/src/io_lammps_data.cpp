// LAMMPS data file export, atom_style sphere (docs/decks.md: beds convert to LAMMPS and
// LIGGGHTS so a study can outgrow one machine).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <limits>

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

namespace {

// Atom types the bed's materials need: the largest material index + 1 (1 without materials).
std::size_t material_types(const Bed& bed) {
  if (bed.material.empty()) return 1;
  return static_cast<std::size_t>(*std::max_element(bed.material.begin(), bed.material.end())) + 1;
}

void check_options(const Bed& bed, const std::string& path, const LammpsDataOptions& o) {
  const std::size_t types = material_types(bed);
  if (o.type_density.size() != 1 && o.type_density.size() != types) {
    throw InputError(fmt::format(
        "{}: {} densities for {} atom types (accepted: one density, or one per material index "
        "0..{})",
        path, o.type_density.size(), types, types - 1));
  }
  for (const double rho : o.type_density) {
    if (!std::isfinite(rho) || !(rho > 0)) {
      throw InputError(fmt::format("{}: density is {:g} (accepted: > 0 kg/m^3)", path, rho));
    }
  }
  if (o.extra_types < 0) throw InputError(path + ": negative count of extra atom types");
}

}  // namespace

void write_lammps_data(const Bed& bed, const std::string& path, double density) {
  LammpsDataOptions options;
  options.type_density = {density};
  write_lammps_data(bed, path, options);
}

void write_lammps_data(const Bed& bed, const std::string& path, const LammpsDataOptions& options) {
  bed.validate(path);
  check_options(bed, path, options);
  // LAMMPS ids start at 1 and are 32-bit in the default (smallbig) build.
  constexpr std::uint64_t max_id = std::numeric_limits<std::int32_t>::max() - 1;
  for (std::uint64_t id : bed.id) {
    if (id > max_id) {
      throw InputError(fmt::format(
          "{}: id {} does not fit a LAMMPS atom id (accepted: ids up to {})", path, id, max_id));
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
  const std::size_t types = material_types(bed);
  auto density = [&](std::size_t i) {
    const std::size_t type = bed.material.empty() ? 0 : bed.material[i];
    return options.type_density.size() == 1 ? options.type_density[0] : options.type_density[type];
  };

  std::string text;
  text.reserve(512 + bed.n() * (bed.has_velocity() ? 9 : 6) * 25);
  char line[512];
  auto append = [&](int len) { text.append(line, static_cast<std::size_t>(len)); };
  text += "LAMMPS data file, atom_style sphere, from powderbed";
  if (!bed.provenance.created_by.empty()) text += " (" + bed.provenance.created_by + ")";
  text += "\n\n# LAMMPS atom id = powderbed id + 1; atom type = material index + 1; density in "
          "kg/m^3 (SI units)\n";
  append(std::snprintf(line, sizeof line, "# boundary %s %s %s\n", d.periodic[0] ? "p" : "f",
                       d.periodic[1] ? "p" : "f",
                       d.dimension == 3 && d.periodic[2] ? "p" : "f"));
  if (d.dimension == 2) {
    text += "# 2D bed: disks in the z = 0 plane, given a z slab of +-r_max; use 'dimension 2' "
            "(density is then mass/area)\n";
  }
  if (widened) text += "# box widened past the bed domain to hold every particle centre\n";
  for (const auto& c : options.comments) text += "# " + c + "\n";
  append(std::snprintf(line, sizeof line, "%zu atoms\n%zu atom types\n\n", bed.n(),
                       types + static_cast<std::size_t>(options.extra_types)));
  append(std::snprintf(line, sizeof line, "%.17g %.17g xlo xhi\n", bx[0], bx[1]));
  append(std::snprintf(line, sizeof line, "%.17g %.17g ylo yhi\n", by[0], by[1]));
  append(std::snprintf(line, sizeof line, "%.17g %.17g zlo zhi\n", bz[0], bz[1]));
  text += "\nAtoms # sphere\n\n";
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const unsigned type = bed.material.empty() ? 1u : bed.material[i] + 1u;
    append(std::snprintf(line, sizeof line, "%llu %u %.17g %.17g %.17g %.17g %.17g\n",
                         static_cast<unsigned long long>(bed.id[i] + 1), type,
                         2.0 * bed.radius[i], density(i), bed.x[i], bed.y[i], bed.z[i]));
  }
  if (bed.has_velocity()) {
    // atom_style sphere's Velocities: id vx vy vz wx wy wz (beds carry no spin: w = 0).
    text += "\nVelocities\n\n";
    for (std::size_t i = 0; i < bed.n(); ++i) {
      append(std::snprintf(line, sizeof line, "%llu %.17g %.17g %.17g 0 0 0\n",
                           static_cast<unsigned long long>(bed.id[i] + 1), bed.vx[i], bed.vy[i],
                           bed.vz[i]));
    }
  }
  detail::AtomicFile file(path);
  detail::write_text(file.temp_path(), path, text);
  file.commit();
}

}  // namespace powderbed::bed
