#pragma once
// The pieces every XDMF sidecar shares (docs/bed-format.md "Seeing true radii in ParaView").
// Particles are a Polyvertex grid whose connectivity is stored: without it ParaView's Xdmf3
// reader (5.11) makes the points but no cells, and filters such as Threshold return nothing.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace powderbed::bed {

// The HDF5 dataset holding the connectivity 0, 1, ..., n-1 (uint64).
inline constexpr const char* kPolyvertexDataset = "/xdmf/polyvertex";

// 0, 1, ..., n-1: one vertex cell per particle.
std::vector<std::uint64_t> polyvertex_connectivity(std::size_t n);

// The <Topology> element of n particles, reading kPolyvertexDataset from `h5` (the HDF5 file's
// name beside the .xmf, XML-escaped), each line prefixed by `indent`.
std::string xdmf_polyvertex_topology(std::size_t n, const std::string& h5,
                                     const std::string& indent);

}  // namespace powderbed::bed
