#pragma once
// The finite-difference substrate under the bed (docs/physics.md §5): a box of nx × ny × nz nodes,
// z from -depth (bottom, k = 0) to the bed's floor (top, k = nz - 1). Node-centred finite
// volumes: interior nodes own dx dy dz, top nodes the half cell below the surface (the half-cell
// balance docs/physics.md §5 describes for the top flux). Dirichlet T = T0 on the four sides and the bottom.
// Face conductivity K_face = (K_a + K_b) / 2; second-order central differences.
#include <cstddef>
#include <utility>
#include <vector>

#include "powderbed/bed/height_map.hpp"

namespace powderbed::thermal {

struct SubstrateGeometry {
  std::size_t nx = 0, ny = 0, nz = 0;
  double x0 = 0, y0 = 0, z_top = 0;  // lower corner of the top face
  double dx = 0, dy = 0, dz = 0;

  std::size_t index(std::size_t i, std::size_t j, std::size_t k) const {
    return i + nx * (j + ny * k);
  }
  std::size_t size() const { return nx * ny * nz; }
  double x(std::size_t i) const { return x0 + dx * static_cast<double>(i); }
  double y(std::size_t j) const { return y0 + dy * static_cast<double>(j); }
  double z(std::size_t k) const { return z_top - dz * static_cast<double>(nz - 1 - k); }
  bool fixed(std::size_t i, std::size_t j, std::size_t k) const {
    return i == 0 || j == 0 || k == 0 || i + 1 == nx || j + 1 == ny;
  }
  // Whether a node of the top face is a Dirichlet node.
  bool fixed_top(std::size_t node) const {
    const std::size_t i = node % nx, j = (node / nx) % ny;
    return i == 0 || j == 0 || i + 1 == nx || j + 1 == ny;
  }
  // Control volume of a free node (half a cell at the top).
  double volume(std::size_t k) const { return dx * dy * dz * (k + 1 == nz ? 0.5 : 1.0); }
};

// The substrate's four corner nodes around (x, y) on the top face with bilinear weights
// (summing to 1): how a particle contact is spread over the grid cell under it.
struct TopStencil {
  std::size_t node[4];
  double weight[4];
};
TopStencil top_stencil(const SubstrateGeometry& g, double x, double y);

// The top nodes whose (x, y) lie within a disc of radius a centred over (x, y), equally weighted
// (their cells are equal), or the bilinear corners when the disc covers no node: what a spread
// cap touches (wetting) and where a fused particle's volume goes (fusion). Weights sum to 1.
std::vector<std::pair<std::size_t, double>> top_footprint(const SubstrateGeometry& g, double x,
                                                          double y, double a);

// The solid's top surface over the grid: per top-face column i + nx j the height z of the solid
// there, at or above the grid's top face z_top (fusion raises it); empty: flat at z_top.
// The solver lumps the solid between z_top and the column's height into the column's top node
// (docs/sinter.md "Fusion").
using TopHeight = std::vector<double>;
// The top at (x, y), bilinear in the column heights.
double top_height_at(const SubstrateGeometry& g, const TopHeight& top, double x, double y);
// The same surface as a height map over the top face's nodes (empty when `top` is: the flat
// plate), for the spreading run's floor (dem/spread.hpp SpreadSettings::floor).
bed::HeightMap top_surface(const SubstrateGeometry& g, const TopHeight& top);

}  // namespace powderbed::thermal
