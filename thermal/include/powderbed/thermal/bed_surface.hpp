#pragma once
// What the laser and the surroundings see of a bed (docs/physics.md §5): which particles are exposed at
// the top (they alone convect and radiate), how deep each particle lies below the top surface
// (Beer–Lambert), and the layer height, porosity and mean diameter that give beta.
#include <cstdint>
#include <vector>

#include "powderbed/bed/bed.hpp"

namespace powderbed::thermal {

struct BedSurface {
  std::vector<std::uint8_t> exposed;  // 1: visible from above at some point of the height map
  std::vector<double> depth;          // top surface above the particle's column minus its top, m
  double layer_height = 0;            // median particle top above the substrate, m (0: no bed)
  double porosity = 1;                // 1 - packing density of [substrate, layer_height]
  double mean_diameter = 0;           // m
  double sample_spacing = 0;          // of the height map, m
  // The height map: highest sphere surface above each sample, relative to the substrate
  // (0 where no particle covers the sample), samples at x0 + k h, y0 + j h, row-major in y.
  std::size_t samples_x = 0, samples_y = 0;
  double x0 = 0, y0 = 0;
  std::vector<double> column;
  // Height of the bed's column over (x, y): the nearest sample (0 outside the map).
  double column_height(double x, double y) const;
};

// Height map on a square raster of spacing min(smallest radius / 2, mean diameter / 8) (at most
// 4e6 samples): each sample holds the highest sphere surface above it and its owner. A particle
// is exposed when it owns a sample or lies at the surface over its own centre.
BedSurface analyse_surface(const bed::Bed& bed, double substrate_top);

}  // namespace powderbed::thermal
