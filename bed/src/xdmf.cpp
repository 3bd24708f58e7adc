#include "powderbed/bed/xdmf.hpp"

#include <numeric>
#include <sstream>

namespace powderbed::bed {

std::vector<std::uint64_t> polyvertex_connectivity(std::size_t n) {
  std::vector<std::uint64_t> c(n);
  std::iota(c.begin(), c.end(), std::uint64_t{0});
  return c;
}

std::string xdmf_polyvertex_topology(std::size_t n, const std::string& h5,
                                     const std::string& indent) {
  const std::string count = std::to_string(n);
  return indent + "<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + count +
         "\" NodesPerElement=\"1\">\n" + indent + "  <DataItem Dimensions=\"" + count +
         "\" NumberType=\"UInt\" Precision=\"8\" Format=\"HDF\">" + h5 + ":" +
         kPolyvertexDataset + "</DataItem>\n" + indent + "</Topology>\n";
}

namespace {

void data_item(std::ostringstream& x, const std::string& dims, const XdmfField& f,
               const std::string& h5) {
  x << "      <DataItem Dimensions=\"" << dims << "\" NumberType=\""
    << (f.bytes ? "UChar" : "Float") << "\" Precision=\"" << (f.bytes ? 1 : 8)
    << "\" Format=\"HDF\">" << h5 << ":" << f.dataset << "</DataItem>\n";
}

}  // namespace

std::string xdmf_particle_series(const std::string& name, std::size_t n, const std::string& h5,
                                 const std::vector<XdmfParticleStep>& steps) {
  const std::string count = std::to_string(n), rows = count + " 3";
  std::ostringstream x;
  x.precision(17);  // times round-trip
  x << "  <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const XdmfParticleStep& s : steps) {
    x << "    <Grid Name=\"" << name << " step " << s.step << "\" GridType=\"Uniform\">\n"
      << "     <Time Value=\"" << s.time << "\"/>\n"
      << xdmf_polyvertex_topology(n, h5, "     ") << "     <Geometry GeometryType=\"XYZ\">\n";
    data_item(x, rows, {"position", s.position, true}, h5);
    x << "     </Geometry>\n";
    for (const XdmfField& f : s.fields) {
      x << "     <Attribute Name=\"" << f.name << "\" AttributeType=\""
        << (f.vector ? "Vector" : "Scalar") << "\" Center=\"Node\">\n";
      data_item(x, f.vector ? rows : count, f, h5);
      x << "     </Attribute>\n";
    }
    x << "    </Grid>\n";
  }
  x << "  </Grid>\n";
  return x.str();
}

std::string xdmf_document(const std::string& grids) {
  return "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n" + grids +
         " </Domain>\n</Xdmf>\n";
}

}  // namespace powderbed::bed
