#include "powderbed/bed/xdmf.hpp"

#include <numeric>

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

}  // namespace powderbed::bed
