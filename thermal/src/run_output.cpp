#include "powderbed/thermal/run_output.hpp"

#include <cstdint>

#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/xdmf.hpp"
#include "run_xdmf.hpp"

namespace powderbed::thermal {

namespace {

// The nodes of the mid plane across `axis`: x = Lx/2 (axis 0, nz × ny) or y = Ly/2 (axis 1,
// nz × nx), z slowest.
std::vector<double> mid_section(const SubstrateGeometry& g, const std::vector<double>& f,
                                int axis) {
  const std::size_t across = axis == 0 ? g.ny : g.nx;
  std::vector<double> out;
  out.reserve(g.nz * across);
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t a = 0; a < across; ++a)
      out.push_back(f[axis == 0 ? g.index(g.nx / 2, a, k) : g.index(a, g.ny / 2, k)]);
  return out;
}
// Each column's top node (ny × nx): the plate's top face, or the raised solid's top.
std::vector<double> top_face(const SubstrateGeometry& g, const std::vector<std::uint32_t>& plane,
                             const std::vector<double>& f) {
  std::vector<double> out(g.columns());
  for (std::size_t c = 0; c < out.size(); ++c) out[c] = f[g.node(c, plane[c])];
  return out;
}

}  // namespace

struct RunWriter::Impl {
  bed::H5Output out;
  std::size_t n;
  SubstrateGeometry g;
  bool full;
  std::vector<std::pair<std::uint64_t, double>> steps;
  bool fused = false, lof = false;
  std::size_t part_cells = 0;  // planes of /part's cells (0: no /part)
  Impl(const std::string& path, std::size_t count, const SubstrateGeometry& grid, bool full_fields)
      : out(path), n(count), g(grid), full(full_fields) {}
};

RunWriter::RunWriter(const std::string& path, const bed::Bed& bed, const Sinter& sinter,
                     bool full_fields)
    : impl_(std::make_unique<Impl>(path, bed.n(), sinter.grid(), full_fields)) {
  bed::H5Output& out = impl_->out;
  out.attribute("/", "format", std::string("powderbed.sinter-run"));
  out.attribute("/", "version", std::uint64_t{1});
  out.attribute("/", "created_by", bed.provenance.created_by);
  out.attribute("/", "command_line", bed.provenance.command_line);
  out.attribute("/provenance", "scene", bed.provenance.scene);
  std::vector<double> xyz(3 * bed.n());
  for (std::size_t i = 0; i < bed.n(); ++i) {
    xyz[3 * i] = bed.x[i];
    xyz[3 * i + 1] = bed.y[i];
    xyz[3 * i + 2] = bed.z[i];
  }
  out.write("/particles/position", xyz, {bed.n(), 3}, "m");
  out.write("/particles/radius", bed.radius, {bed.n()}, "m");
  out.write("/particles/id", bed.id, {bed.n()}, "1");
  out.write(bed::kPolyvertexDataset, bed::polyvertex_connectivity(bed.n()), {bed.n()}, "1");
  const SubstrateGeometry& g = impl_->g;
  out.attribute("/substrate", "origin", std::vector<double>{g.x0, g.y0, g.z_top});
  out.attribute("/substrate", "spacing", std::vector<double>{g.dx, g.dy, g.dz});
  out.attribute("/substrate", "nodes", std::vector<double>{static_cast<double>(g.nx),
                                                           static_cast<double>(g.ny),
                                                           static_cast<double>(g.nz)});
  // The plate's top plane k (its nodes at z = origin z): planes above it are the part's room.
  out.attribute("/substrate", "plate_plane", static_cast<std::uint64_t>(g.k_plate()));
}

RunWriter::~RunWriter() = default;

void RunWriter::snapshot(const Sinter& sinter) {
  Impl& s = *impl_;
  const std::string group = bed::step_group(sinter.step());
  s.out.attribute(group, "time", sinter.time());
  s.out.attribute(group, "step", sinter.step());
  s.out.write(group + "/particle_temperature", sinter.particle_temperature(), {s.n}, "K");
  s.out.write(group + "/particle_phase", sinter.particle_phase(), {s.n}, "1");
  const auto& t = sinter.substrate_temperature();
  s.out.write(group + "/section_y", mid_section(s.g, t, 1), {s.g.nz, s.g.nx}, "K");
  s.out.write(group + "/top", top_face(s.g, sinter.top_planes(), t), {s.g.ny, s.g.nx}, "K");
  if (s.full) {
    const std::vector<float> field(t.begin(), t.end());
    s.out.write(group + "/substrate", field, {s.g.nz, s.g.ny, s.g.nx}, "K");
  }
  s.steps.emplace_back(sinter.step(), sinter.time());
}

void RunWriter::fusion(const Fusion& f) {
  Impl& s = *impl_;
  const SubstrateGeometry& g = s.g;
  s.out.write("/fusion/top_height", f.top, {g.ny, g.nx}, "m");
  // For ParaView: the surface's points and its height above the plate.
  std::vector<double> surface, height;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const double z = f.top[i + g.nx * j];
      surface.insert(surface.end(), {g.x(i), g.y(j), z});
      height.push_back(z - g.z_top);
    }
  s.out.write("/fusion/surface", surface, {g.ny, g.nx, 3}, "m");
  s.out.write("/fusion/height", height, {g.ny, g.nx}, "m");
  s.fused = true;
  s.out.write("/fusion/state", f.state, {s.n}, "1");
  s.out.attribute("/fusion", "threshold", f.threshold);
  s.out.attribute("/fusion", "fused", static_cast<std::uint64_t>(f.fused));
  s.out.attribute("/fusion", "vaporised", static_cast<std::uint64_t>(f.vaporised));
  s.out.attribute("/fusion", "balled", static_cast<std::uint64_t>(f.balled));
  s.out.attribute("/fusion", "powder_mass_before", f.powder_mass_before);
  s.out.attribute("/fusion", "powder_mass_after", f.powder_mass_after);
  s.out.attribute("/fusion", "solid_mass_before", f.solid_mass_before);
  s.out.attribute("/fusion", "solid_mass_after", f.solid_mass_after);
  s.out.attribute("/fusion", "vaporised_mass", f.vaporised_mass);
  s.out.attribute("/fusion", "mass_error", f.mass_error());
}

void RunWriter::lack_of_fusion(const LackOfFusion& lof) {
  Impl& s = *impl_;
  s.out.write("/fusion/lack_of_fusion", lof.map, {s.g.ny, s.g.nx}, "1");
  s.out.attribute("/fusion", "lack_of_fusion_fraction", lof.fraction());
  s.out.attribute("/fusion", "scanned_columns", static_cast<std::uint64_t>(lof.scanned));
  s.out.attribute("/fusion", "unbonded_columns", static_cast<std::uint64_t>(lof.unbonded));
  s.lof = true;
}

void RunWriter::part(const PartRecord& record) {
  write_part_record(impl_->out, record);
  impl_->part_cells = part_field(record).nk;
}

void RunWriter::finish(const Sinter& sinter, const SinterResult& result,
                       const std::vector<std::pair<std::string, double>>& summary) {
  Impl& s = *impl_;
  const SubstrateGeometry& g = s.g;
  const auto& peak = sinter.substrate_peak();
  s.out.write("/melt/particle", sinter.particle_max_temperature(), {s.n}, "K");
  s.out.write("/melt/section_x", mid_section(g, peak, 0), {g.nz, g.ny}, "K");
  s.out.write("/melt/section_y", mid_section(g, peak, 1), {g.nz, g.nx}, "K");
  s.out.write("/melt/top", top_face(g, sinter.top_planes(), peak), {g.ny, g.nx}, "K");
  s.out.attribute("/melt", "height", result.melt_pool.height);
  s.out.attribute("/melt", "width", result.melt_pool.width);
  s.out.attribute("/melt", "depth", result.melt_pool.depth);
  s.out.attribute("/melt", "x_plane", g.x(g.nx / 2));
  s.out.attribute("/melt", "melting_point", sinter.material().phase_change().melting_point);
  const auto& tracks = result.tracks;
  const auto column = [&](const char* name, const char* units, auto field) {
    std::vector<double> v;
    for (const auto& t : tracks) v.push_back(field(t));
    s.out.write(std::string("/tracks/") + name, v, {tracks.size()}, units);
  };
  column("width", "m", [](const TrackStats& t) { return t.pool.width; });
  column("depth", "m", [](const TrackStats& t) { return t.pool.depth; });
  column("height", "m", [](const TrackStats& t) { return t.pool.height; });
  column("length", "m", [](const TrackStats& t) { return t.length; });
  column("peak_temperature", "K", [](const TrackStats& t) { return t.peak_temperature; });
  column("start_temperature", "K", [](const TrackStats& t) { return t.start_temperature; });
  column("stored_energy", "J", [](const TrackStats& t) { return t.stored_energy; });
  column("particles_molten", "1",
         [](const TrackStats& t) { return static_cast<double>(t.particles_molten); });
  column("t_start", "s", [](const TrackStats& t) { return t.t_start; });
  column("t_end", "s", [](const TrackStats& t) { return t.t_end; });
  for (const auto& [name, value] : summary) s.out.attribute("/summary", name, value);

  s.out.commit();
  bed::write_text_file(bed::xdmf_sidecar_path(s.out.path()),
                       detail::run_xdmf(bed::file_name_of(s.out.path()), s.n, g, s.steps, s.fused, s.lof,
                                        s.part_cells));
}

}  // namespace powderbed::thermal
