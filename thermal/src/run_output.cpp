#include "powderbed/thermal/run_output.hpp"

#include <sstream>

#include "powderbed/bed/h5_output.hpp"

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
std::vector<double> top_face(const SubstrateGeometry& g, const std::vector<double>& f) {
  const auto first = f.begin() + static_cast<std::ptrdiff_t>(g.index(0, 0, g.nz - 1));
  return std::vector<double>(first, first + static_cast<std::ptrdiff_t>(g.nx * g.ny));
}

}  // namespace

struct RunWriter::Impl {
  bed::H5Output out;
  std::size_t n;
  SubstrateGeometry g;
  bool full;
  std::vector<std::pair<std::uint64_t, double>> steps;
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
  out.write("/particles/position", xyz, {bed.n(), 3});
  out.write("/particles/radius", bed.radius, {bed.n()});
  out.write("/particles/id", bed.id, {bed.n()});
  const SubstrateGeometry& g = impl_->g;
  out.attribute("/substrate", "origin", std::vector<double>{g.x0, g.y0, g.z_top});
  out.attribute("/substrate", "spacing", std::vector<double>{g.dx, g.dy, g.dz});
  out.attribute("/substrate", "nodes", std::vector<double>{static_cast<double>(g.nx),
                                                           static_cast<double>(g.ny),
                                                           static_cast<double>(g.nz)});
}

RunWriter::~RunWriter() = default;

void RunWriter::snapshot(const Sinter& sinter) {
  Impl& s = *impl_;
  const std::string group = "/steps/" + std::to_string(sinter.step());
  s.out.attribute(group, "time", sinter.time());
  s.out.attribute(group, "step", sinter.step());
  s.out.write(group + "/particle_temperature", sinter.particle_temperature(), {s.n});
  s.out.write(group + "/particle_phase", sinter.particle_phase(), {s.n});
  const auto& t = sinter.substrate_temperature();
  s.out.write(group + "/section_y", mid_section(s.g, t, 1), {s.g.nz, s.g.nx});
  s.out.write(group + "/top", top_face(s.g, t), {s.g.ny, s.g.nx});
  if (s.full) {
    const std::vector<float> field(t.begin(), t.end());
    s.out.write(group + "/substrate", field, {s.g.nz, s.g.ny, s.g.nx});
  }
  s.steps.emplace_back(sinter.step(), sinter.time());
}

void RunWriter::finish(const Sinter& sinter, const SinterResult& result,
                       const std::vector<std::pair<std::string, double>>& summary) {
  Impl& s = *impl_;
  const SubstrateGeometry& g = s.g;
  const auto& peak = sinter.substrate_peak_planes();
  s.out.write("/melt/particle", sinter.particle_max_temperature(), {s.n});
  s.out.write("/melt/section_x", mid_section(g, peak, 0), {g.nz, g.ny});
  s.out.write("/melt/section_y", mid_section(g, peak, 1), {g.nz, g.nx});
  s.out.write("/melt/top", top_face(g, peak), {g.ny, g.nx});
  s.out.attribute("/melt", "height", result.melt_pool.height);
  s.out.attribute("/melt", "width", result.melt_pool.width);
  s.out.attribute("/melt", "depth", result.melt_pool.depth);
  s.out.attribute("/melt", "x_plane", g.x(g.nx / 2));
  s.out.attribute("/melt", "melting_point", sinter.material().phase_change().melting_point);
  for (const auto& [name, value] : summary) s.out.attribute("/summary", name, value);

  // XDMF: per step a spatial collection of the particles, the top face and the y section.
  const std::string h5 = bed::file_name_of(s.out.path());
  std::ostringstream x;
  x.precision(17);
  const auto item = [&](const std::string& dims, const std::string& path, int precision = 8) {
    x << "      <DataItem Dimensions=\"" << dims << "\" NumberType=\"" << (precision == 1 ? "UChar" : "Float")
      << "\" Precision=\"" << precision << "\" Format=\"HDF\">" << h5 << ":" << path
      << "</DataItem>\n";
  };
  const std::string n = std::to_string(s.n);
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"sinter\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& [step, time] : s.steps) {
    const std::string group = "/steps/" + std::to_string(step);
    x << "   <Grid Name=\"step " << step << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
      << "    <Time Value=\"" << time << "\"/>\n";
    x << "    <Grid Name=\"particles\" GridType=\"Uniform\">\n"
      << "     <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\"/>\n"
      << "     <Geometry GeometryType=\"XYZ\">\n";
    item(n + " 3", "/particles/position");
    x << "     </Geometry>\n     <Attribute Name=\"radius\" Center=\"Node\">\n";
    item(n, "/particles/radius");
    x << "     </Attribute>\n     <Attribute Name=\"temperature\" Center=\"Node\">\n";
    item(n, group + "/particle_temperature");
    x << "     </Attribute>\n     <Attribute Name=\"phase\" Center=\"Node\">\n";
    item(n, group + "/particle_phase", 1);
    x << "     </Attribute>\n    </Grid>\n";
    // CoRectMesh: dimensions and origin/spacing in z, y, x order.
    const auto plane = [&](const char* name, std::size_t nz, std::size_t ny, std::size_t nx,
                           double oz, double oy, const std::string& data) {
      const std::string dims = std::to_string(nz) + " " + std::to_string(ny) + " " + std::to_string(nx);
      x << "    <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n"
        << "     <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << dims << "\"/>\n"
        << "     <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
        << "      <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
        << oz << " " << oy << " " << g.x0 << "</DataItem>\n"
        << "      <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
        << g.dz << " " << g.dy << " " << g.dx << "</DataItem>\n"
        << "     </Geometry>\n     <Attribute Name=\"temperature\" Center=\"Node\">\n";
      item(dims, data);
      x << "     </Attribute>\n    </Grid>\n";
    };
    plane("top", 1, g.ny, g.nx, g.z_top, g.y0, group + "/top");
    plane("section_y", g.nz, 1, g.nx, g.z(0), g.y(g.ny / 2), group + "/section_y");
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  s.out.commit();
  bed::write_text_file(bed::xdmf_sidecar_path(s.out.path()), x.str());
}

}  // namespace powderbed::thermal
