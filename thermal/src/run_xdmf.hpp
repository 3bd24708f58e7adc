#pragma once
// The XDMF sidecar of a sinter run (docs/bed-format.md "A sinter run in ParaView"): three named
// temporal collections, "particles" (Polyvertex), "top" (the substrate's top face) and
// "section_y" (the substrate on y = Ly/2), so ParaView lists them as three blocks that can be
// shown, hidden and filtered one by one; with fusion a fourth, "solid_top" (the solid's raised
// top surface after the scan, its height above the plate as "height", and with a build's
// lack-of-fusion map that map as "lack_of_fusion"); with a build's part record a fifth, "part" (its
// cells' solid and never-molten fractions, part_porosity.hpp).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "powderbed/thermal/substrate.hpp"

namespace powderbed::thermal::detail {

// `h5`: the run file's name beside the .xmf; `steps`: (step, time) in time order.
std::string run_xdmf(const std::string& h5, std::size_t particles, const SubstrateGeometry& g,
                     const std::vector<std::pair<std::uint64_t, double>>& steps, bool fused,
                     bool lack_of_fusion, std::size_t part_cells);

}  // namespace powderbed::thermal::detail
