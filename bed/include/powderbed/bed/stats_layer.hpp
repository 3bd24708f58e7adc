#pragma once
// Statistics of one spread layer (docs/spread-layer.md): the powder a recoater leaves between the
// build plate z = plate and the layer top z = plate + gap, over an x window that leaves out the
// ends of the strip (where the tool starts and where the heap is left). 3D beds only.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/psd.hpp"

namespace powderbed::bed {

struct LayerRequest {
  double plate = 0;        // z of the build plate (m)
  double gap = 0;          // layer thickness: top = plate + gap (m), > 0
  double x0 = 0, x1 = 0;   // the window in x (m), x0 < x1, inside the domain
  double raster = 0;       // side of a height-map cell (m), > 0; cells are fitted to the window
  std::size_t segregation_bins = 10;  // x bins of the mean diameter, >= 1
};

// The top view: the surface height above the plate at each cell centre, row-major with x
// fastest (height[iy * nx + ix]), 0 over bare plate (covered[...] == 0 there). Not named
// HeightMap: height_map.hpp's (the solid's top) has that name, and a program linking both (the
// Python module: bedstat's statistics and the spread) had two types of one name (-Wodr).
struct LayerHeightMap {
  double x0 = 0, y0 = 0;  // lower corner of the raster (m)
  double dx = 0, dy = 0;  // cell sides (m)
  std::size_t nx = 0, ny = 0;
  std::vector<double> height;  // m above the plate
  std::vector<char> covered;   // 1 where a sphere lies over the cell centre
};

struct Segregation {
  std::vector<double> x;              // bin centres (m)
  std::vector<double> mean_diameter;  // mean diameter of the layer particles in the bin (m; NaN if empty)
  std::vector<std::size_t> count;     // layer particles per bin
  double slope = 0;                   // d(diameter)/dx of the least-squares line (m/m; NaN if < 2 x values)
};

struct LayerStats {
  LayerRequest request;
  std::size_t particles = 0;  // layer particles: centre in [plate, plate + gap] and in the window
  double density = 0;         // solid volume in window x [y] x [plate, plate + gap] / that volume
  double coverage = 0;        // fraction of the window's plate area under powder (raster)
  double mean_height = 0;     // mean surface height above the plate over the raster (m)
  double sa = 0, sq = 0;      // mean absolute and RMS deviation of the heights from that mean (m)
  LayerHeightMap map;
  Segregation segregation;
  std::vector<double> diameters;  // of the layer particles (m), for the PSD against the feed
};

// Everything above; throws InputError naming the field for a 2D bed, gap <= 0, a window outside
// the domain or empty, raster <= 0 or one that would need more than 1e8 cells, bins == 0.
LayerStats layer_stats(const Bed& bed, const LayerRequest& request);

// Solid volume inside the axis-aligned box [lo, hi] (3D; +-infinity for an unbounded side),
// spheres cut exactly by its faces, periodic images counted where a periodic axis is bounded.
double solid_volume_in_box(const Bed& bed, const std::array<double, 3>& lo,
                           const std::array<double, 3>& hi);

// Top-view raster of the spheres that reach into [plate, top] over the window, as a height
// field: h(x, y) = max_i z_i + sqrt(r_i^2 - |(x, y) - (x_i, y_i)|^2) - plate. The request as
// layer_stats checks it (the pieces below do not check again).
LayerHeightMap height_map(const Bed& bed, const LayerRequest& request);

// Surface texture of a height map (ISO 25178): mean height, Sa = mean |h - mean|,
// Sq = sqrt(mean (h - mean)^2), and the covered fraction.
struct SurfaceTexture {
  double mean = 0, sa = 0, sq = 0, coverage = 0;
};
SurfaceTexture surface_texture(const LayerHeightMap& map);

// Mean diameter in `bins` equal x bins of [x0, x1] and the least-squares slope of diameter
// against x over the particles themselves (centres `x`, diameters `d`).
Segregation size_segregation(const std::vector<double>& x, const std::vector<double>& d,
                             double x0, double x1, std::size_t bins);

// Kolmogorov–Smirnov test of two size samples or of a sample against a PSD.
struct KsTest {
  double d = 0;  // sup |F_1 - F_2|
  double p = 1;  // asymptotic p-value (Kolmogorov distribution with Stephens' small-n factor)
  std::size_t n1 = 0, n2 = 0;  // sample sizes (n2 = 0 against a PSD)
};
KsTest ks_two_sample(std::vector<double> a, std::vector<double> b);
// One sample of diameters (m) against a PSD (whose CDF is of the radius).
KsTest ks_against_psd(const std::vector<double>& diameters, const Psd& psd);
// Q_KS(lambda) = 2 sum_{k>=1} (-1)^(k-1) exp(-2 k^2 lambda^2), the Kolmogorov tail probability.
double kolmogorov_tail(double lambda);

// The height map as CSV "x,y,height,covered" (cell centres, m; covered 0/1), written atomically.
void write_height_map_csv(const LayerHeightMap& map, const std::string& path);

}  // namespace powderbed::bed
