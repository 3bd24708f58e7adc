#include "powderbed/thermal/part_porosity.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_input.hpp"
#include "powderbed/bed/h5_output.hpp"

namespace powderbed::thermal {

namespace {

constexpr const char* kGroup = "/part";

// Keeps of `cut` what lies below `z` (the melt took what is above it).
void melt_above(std::vector<HeightInterval>& cut, double z) {
  for (auto& s : cut) s.hi = std::min(s.hi, z);
  std::erase_if(cut, [](const HeightInterval& s) { return !(s.hi > s.lo); });
}

// Keeps of `column` what lies in [low, high].
void clip(std::vector<HeightInterval>& column, double low, double high) {
  for (auto& s : column) {
    s.lo = std::max(s.lo, low);
    s.hi = std::min(s.hi, high);
  }
  std::erase_if(column, [](const HeightInterval& s) { return !(s.hi > s.lo); });
}

bool same_columns(const PartRecord& r, const SubstrateGeometry& g) {
  const auto near = [](double a, double b, double d) { return std::abs(a - b) <= 1e-9 * d; };
  return r.nx == g.nx && r.ny == g.ny && near(r.x0, g.x0, g.dx) && near(r.y0, g.y0, g.dy) &&
         near(r.dx, g.dx, g.dx) && near(r.dy, g.dy, g.dy) && near(r.z_top, g.z_top, g.dz);
}

// The length of [lo, hi] inside [a, b].
double overlap(double lo, double hi, double a, double b) {
  return std::max(0.0, std::min(hi, b) - std::max(lo, a));
}

}  // namespace

PartRecord part_record(const SubstrateGeometry& g) {
  PartRecord r;
  r.nx = g.nx;
  r.ny = g.ny;
  r.x0 = g.x0;
  r.y0 = g.y0;
  r.dx = g.dx;
  r.dy = g.dy;
  r.dz = g.dz;
  r.z_top = g.z_top;
  r.top.assign(g.columns(), g.z_top);
  r.below_last.assign(g.columns(), g.z_top);
  r.scanned.assign(g.columns(), 0);
  r.never_molten.assign(g.columns(), {});
  return r;
}

void check_part_grid(const PartRecord& r, const SubstrateGeometry& g) {
  if (!same_columns(r, g))
    throw InputError(fmt::format("part record: its {} x {} columns ({:g} x {:g} m apart) are not the "
                                 "scan grid's {} x {} ({:g} x {:g} m) (accepted: the same substrate "
                                 "grid every layer)",
                                 r.nx, r.ny, r.dx, r.dy, g.nx, g.ny, g.dx, g.dy));
}

void record_layer(PartRecord& r, const Sinter& sinter, const Fusion& f, const LackOfFusion& lof) {
  const SubstrateGeometry& g = sinter.grid();
  check_part_grid(r, g);
  const auto& peak = sinter.substrate_peak();
  const auto& plane = sinter.top_planes();
  for (std::size_t c = 0; c < g.columns(); ++c) {
    auto& column = r.never_molten[c];
    melt_above(column, molten_bottom(g, peak, c, plane[c], lof.threshold));
    // The captured powder lies on the melt's deposit; at a periodic seam the joined top may
    // stand below the melt's own, and then nothing of it is captured powder.
    if (f.top[c] > f.melt_top[c]) column.push_back({f.melt_top[c], f.top[c]});
    clip(column, g.z_top, f.top[c]);
    r.below_last[c] = r.top[c];
    r.top[c] = f.top[c];
    r.scanned[c] += lof.map[c] != kNotScanned ? 1 : 0;
  }
  ++r.layers;
}

namespace {

// The porosity of the core's solid from the plate up to `limit` (per column; the part's top
// where that is lower).
PartPorosity porosity_below(const PartRecord& r, const TopHeight& limit) {
  PartPorosity p;
  if (r.layers == 0) return p;
  const double area = r.dx * r.dy;
  for (std::size_t c = 0; c < r.columns(); ++c) {
    if (r.scanned[c] != r.layers) continue;
    ++p.core_columns;
    const double high = std::min(limit[c], r.top[c]);
    p.volume += area * std::max(0.0, high - r.z_top);
    for (const auto& s : r.never_molten[c]) p.never_molten += area * overlap(s.lo, s.hi, r.z_top, high);
  }
  return p;
}

}  // namespace

PartPorosity part_porosity(const PartRecord& r) { return porosity_below(r, r.top); }

PartPorosity interior_porosity(const PartRecord& r) { return porosity_below(r, r.below_last); }

PartField part_field(const PartRecord& r) {
  PartField out;
  if (r.empty()) return out;
  const double highest = *std::max_element(r.top.begin(), r.top.end());
  out.nk = static_cast<std::size_t>(std::ceil((highest - r.z_top) / r.dz - 1e-9));
  out.solid.assign(out.nk * r.columns(), 0.0);
  out.never_molten.assign(out.nk * r.columns(), 0.0);
  for (std::size_t k = 0; k < out.nk; ++k) {
    const double a = r.z_top + r.dz * static_cast<double>(k), b = a + r.dz;
    for (std::size_t c = 0; c < r.columns(); ++c) {
      const std::size_t cell = c + r.columns() * k;
      out.solid[cell] = overlap(r.z_top, r.top[c], a, b) / r.dz;
      for (const auto& s : r.never_molten[c]) out.never_molten[cell] += overlap(s.lo, s.hi, a, b) / r.dz;
    }
  }
  return out;
}

void write_part_record(bed::H5Output& out, const PartRecord& r) {
  out.attribute(kGroup, "layers", r.layers);
  out.attribute(kGroup, "nx", static_cast<std::uint64_t>(r.nx));
  out.attribute(kGroup, "ny", static_cast<std::uint64_t>(r.ny));
  const std::pair<const char*, double> grid[] = {{"x0", r.x0}, {"y0", r.y0}, {"dx", r.dx},
                                                 {"dy", r.dy}, {"dz", r.dz}, {"z_top", r.z_top}};
  for (const auto& [name, value] : grid) out.attribute(kGroup, name, value);
  const std::string g = kGroup;
  out.write(g + "/top", r.top, {r.ny, r.nx}, "m");
  out.write(g + "/below_last", r.below_last, {r.ny, r.nx}, "m");
  out.write(g + "/scanned", r.scanned, {r.ny, r.nx}, "1");
  std::vector<double> rows;
  for (std::size_t c = 0; c < r.columns(); ++c)
    for (const auto& s : r.never_molten[c]) rows.insert(rows.end(), {static_cast<double>(c), s.lo, s.hi});
  out.write(g + "/never_molten", rows, {rows.size() / 3, 3}, "1 (column), m (lo, hi)");
  const PartField field = part_field(r);
  out.write(g + "/solid_fraction", field.solid, {field.nk, r.ny, r.nx}, "1");
  out.write(g + "/never_molten_fraction", field.never_molten, {field.nk, r.ny, r.nx}, "1");
  const PartPorosity p = part_porosity(r);
  out.attribute(kGroup, "porosity", p.fraction());
  out.attribute(kGroup, "interior_porosity", interior_porosity(r).fraction());
  out.attribute(kGroup, "core_columns", static_cast<std::uint64_t>(p.core_columns));
}

PartRecord read_part_record(const std::string& path) {
  const bed::H5Input in(path);
  PartRecord r;
  if (!in.exists(kGroup)) return r;
  const std::string g = kGroup;
  const auto real = [&](const char* name) { return in.double_attribute(kGroup, name); };
  r.layers = in.uint64_attribute(kGroup, "layers");
  r.nx = in.uint64_attribute(kGroup, "nx");
  r.ny = in.uint64_attribute(kGroup, "ny");
  r.x0 = real("x0");
  r.y0 = real("y0");
  r.dx = real("dx");
  r.dy = real("dy");
  r.dz = real("dz");
  r.z_top = real("z_top");
  r.top = in.read_doubles(g + "/top", r.nx);
  if (!in.exists(g + "/below_last"))
    throw InputError(fmt::format("{}: /part has no below_last, the part's top before its last layer "
                                 "(accepted: a layer file written by this version of build)", path));
  r.below_last = in.read_doubles(g + "/below_last", r.nx);
  r.scanned = in.read_uint64s(g + "/scanned", r.nx);
  const auto rows = in.read_doubles(g + "/never_molten", 3);
  if (r.top.size() != r.columns() || r.below_last.size() != r.columns() ||
      r.scanned.size() != r.columns() || !(r.dz > 0))
    throw InputError(fmt::format("{}: /part: top, below_last or scanned does not hold {} x {} columns, or dz "
                                 "is not > 0 (accepted: a layer file written by build)",
                                 path, r.nx, r.ny));
  r.never_molten.assign(r.columns(), {});
  for (std::size_t i = 0; i < rows.size(); i += 3) {
    const double c = rows[i];
    if (!(c >= 0 && c < static_cast<double>(r.columns())) || !(rows[i + 2] > rows[i + 1]))
      throw InputError(fmt::format("{}: /part/never_molten: row {} names column {} or an empty "
                                   "interval (accepted: columns 0 to {}, lo < hi)",
                                   path, i / 3, c, r.columns() - 1));
    r.never_molten[static_cast<std::size_t>(c)].push_back({rows[i + 1], rows[i + 2]});
  }
  return r;
}

}  // namespace powderbed::thermal
