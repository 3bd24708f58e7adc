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

// A field of the particles at one time: a dataset of n values (a scalar) or n x 3 (a vector).
struct XdmfField {
  std::string name;     // as ParaView lists it
  std::string dataset;  // its path in the HDF5 file: "/radius", "/steps/000000000025/velocity"
  bool vector = false;  // n x 3
  bool bytes = false;   // uint8 (a phase); float64 otherwise
};

// One time of a particle time series: the n x 3 float64 positions and the fields written at that
// time, and only those (a grid must not name a dataset the file lacks).
struct XdmfParticleStep {
  std::uint64_t step = 0;
  double time = 0;  // s
  std::string position;
  std::vector<XdmfField> fields;
};

// The time series of n particles as a temporal collection `name` of Polyvertex grids, one per
// step ("<name> step <k>"), reading `h5` (as xdmf_polyvertex_topology): ParaView plays it as an
// animation. The text sits in an XDMF document's <Domain> (xdmf_document). Deposit's trajectories
// and sinter's runs write their particles with it.
std::string xdmf_particle_series(const std::string& name, std::size_t n, const std::string& h5,
                                 const std::vector<XdmfParticleStep>& steps);

// An XDMF 3 document whose <Domain> holds `grids`.
std::string xdmf_document(const std::string& grids);

}  // namespace powderbed::bed
