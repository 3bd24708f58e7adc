#pragma once
// The layer density a scan met (docs/build.md "Layers"): the solid fraction of the powder whose
// centres lie over the scanned columns (each column owns dx dy around its node) and below the
// tool's bottom, over the space between the solid's top and the tool's bottom there.
#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/lack_of_fusion.hpp"
#include "powderbed/thermal/substrate.hpp"

namespace powderbed::process {

// `top`: the solid's top before the scan (empty: the plate's top face g.z_top); `bottom`: the
// tool's lowest point, m. 0 when no column was scanned.
double scanned_layer_density(const bed::Bed& bed, const thermal::SubstrateGeometry& g,
                             const thermal::TopHeight& top, const thermal::LackOfFusion& lof,
                             double bottom);

}  // namespace powderbed::process
