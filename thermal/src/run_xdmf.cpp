#include "run_xdmf.hpp"

#include <sstream>

#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/xdmf.hpp"

namespace powderbed::thermal::detail {

namespace {

using Steps = std::vector<std::pair<std::uint64_t, double>>;

struct Writer {
  std::ostringstream x;
  std::string h5;

  void item(const std::string& dims, const std::string& path, bool uchar = false) {
    x << "      <DataItem Dimensions=\"" << dims << "\" NumberType=\""
      << (uchar ? "UChar" : "Float") << "\" Precision=\"" << (uchar ? 1 : 8)
      << "\" Format=\"HDF\">" << h5 << ":" << path << "</DataItem>\n";
  }
  void attribute(const char* name, const std::string& dims, const std::string& path,
                 bool uchar = false) {
    x << "     <Attribute Name=\"" << name << "\" AttributeType=\"Scalar\" Center=\"Node\">\n";
    item(dims, path, uchar);
    x << "     </Attribute>\n";
  }
  void begin_step(const char* what, std::uint64_t step, double time) {
    x << "    <Grid Name=\"" << what << " step " << step << "\" GridType=\"Uniform\">\n"
      << "     <Time Value=\"" << time << "\"/>\n";
  }
};

// The particles' temperature and phase at each snapshot, on the positions and radii of the bed.
std::string particles(const std::string& h5, std::size_t count, const Steps& steps) {
  std::vector<bed::XdmfParticleStep> grids;
  for (const auto& [step, time] : steps) {
    const std::string group = bed::step_group(step);
    grids.push_back({step, time, "/particles/position",
                     {{"radius", "/particles/radius"},
                      {"temperature", group + "/particle_temperature"},
                      {"phase", group + "/particle_phase", false, true}}});
  }
  return bed::xdmf_particle_series("particles", count, h5, grids);
}

// A plane of substrate nodes as a CoRectMesh: dimensions and origin/spacing in z, y, x order.
struct Plane {
  const char* name;     // the collection's name and the dataset under each step group
  std::size_t nz, ny;   // nx is the grid's
  double z0, y0;
};

void plane(Writer& w, const SubstrateGeometry& g, const Plane& p, const Steps& steps) {
  const std::string dims =
      std::to_string(p.nz) + " " + std::to_string(p.ny) + " " + std::to_string(g.nx);
  w.x << "  <Grid Name=\"" << p.name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& [step, time] : steps) {
    w.begin_step(p.name, step, time);
    w.x << "     <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << dims << "\"/>\n"
        << "     <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
        << "      <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
        << p.z0 << " " << p.y0 << " " << g.x0 << "</DataItem>\n"
        << "      <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
        << g.dz << " " << g.dy << " " << g.dx << "</DataItem>\n"
        << "     </Geometry>\n";
    w.attribute("temperature", dims, bed::step_group(step) + "/" + p.name);
    w.x << "    </Grid>\n";
  }
  w.x << "  </Grid>\n";
}

// The fused solid's top: a curvilinear ny × nx surface through /fusion/surface (x, y, z per
// column), at the run's last time.
void solid_top(Writer& w, const SubstrateGeometry& g, double time, bool lack_of_fusion) {
  const std::string dims = std::to_string(g.ny) + " " + std::to_string(g.nx);
  w.x << "  <Grid Name=\"solid_top\" GridType=\"Uniform\">\n"
      << "   <Time Value=\"" << time << "\"/>\n"
      << "   <Topology TopologyType=\"2DSMesh\" Dimensions=\"" << dims << "\"/>\n"
      << "   <Geometry GeometryType=\"XYZ\">\n";
  w.item(dims + " 3", "/fusion/surface");
  w.x << "   </Geometry>\n";
  w.attribute("height", dims, "/fusion/height");
  if (lack_of_fusion) w.attribute("lack_of_fusion", dims, "/fusion/lack_of_fusion", true);
  w.x << "  </Grid>\n";
}

// The part's cells (/part): nk planes of dz from the plate's top, each column's cell centred on
// its node, at the run's last time; cell data, so a Threshold on never_molten_fraction shows
// the pores as blocks.
void part(Writer& w, const SubstrateGeometry& g, std::size_t nk, double time) {
  const std::string cells = std::to_string(nk) + " " + std::to_string(g.ny) + " " + std::to_string(g.nx);
  w.x << "  <Grid Name=\"part\" GridType=\"Uniform\">\n"
      << "   <Time Value=\"" << time << "\"/>\n"
      << "   <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << nk + 1 << " " << g.ny + 1
      << " " << g.nx + 1 << "\"/>\n"
      << "   <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
      << "    <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
      << g.z_top << " " << g.y0 - 0.5 * g.dy << " " << g.x0 - 0.5 * g.dx << "</DataItem>\n"
      << "    <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
      << g.dz << " " << g.dy << " " << g.dx << "</DataItem>\n"
      << "   </Geometry>\n";
  for (const char* name : {"solid_fraction", "never_molten_fraction"}) {
    w.x << "   <Attribute Name=\"" << name << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
    w.item(cells, std::string("/part/") + name);
    w.x << "   </Attribute>\n";
  }
  w.x << "  </Grid>\n";
}

}  // namespace

std::string run_xdmf(const std::string& h5, std::size_t count, const SubstrateGeometry& g,
                     const Steps& steps, bool fused, bool lack_of_fusion, std::size_t part_cells) {
  Writer w;
  w.h5 = h5;
  w.x.precision(17);
  w.x << particles(h5, count, steps);
  plane(w, g, {"top", 1, g.ny, g.z_top, g.y0}, steps);
  plane(w, g, {"section_y", g.nz, 1, g.z(0), g.y(g.ny / 2)}, steps);
  if (fused && !steps.empty()) solid_top(w, g, steps.back().second, lack_of_fusion);
  if (part_cells > 0 && !steps.empty()) part(w, g, part_cells, steps.back().second);
  return bed::xdmf_document(w.x.str());
}

}  // namespace powderbed::thermal::detail
