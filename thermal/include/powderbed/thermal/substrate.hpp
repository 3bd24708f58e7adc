#pragma once
// The finite-difference substrate under the bed (docs/physics.md §5): a box of nx × ny × nz nodes,
// z from -depth (bottom, k = 0) up to the plate's top, the bed's floor (k = k_plate()), and
// nz_above planes over it that a part grown on the plate fills column by column (docs/sinter.md
// "Fusion": each column's top node is the highest node its solid reaches; the nodes above it
// are empty). Node-centred finite volumes: interior nodes own dx dy dz, a column's top node
// the half cell below its node plus the solid above it, less than one dz (the half-cell balance
// docs/physics.md §5 describes for the top flux). Dirichlet T = T0 on the four sides and the
// bottom, or, with periodic_y, on the x sides and the bottom only: the two y sides are then one
// seam (the plate of a strip periodic across y, as a build spreads it), row 0 is free and row
// ny - 1 its image, a copy the grid step refreshes. Face conductivity K_face = (K_a + K_b) / 2;
// second-order central differences.
#include <cstddef>
#include <utility>
#include <vector>

#include "powderbed/bed/height_map.hpp"

namespace powderbed::thermal {

struct SubstrateGeometry {
  std::size_t nx = 0, ny = 0, nz = 0;
  std::size_t nz_above = 0;          // planes over the plate's top, for a part to grow into
  double x0 = 0, y0 = 0, z_top = 0;  // lower corner of the plate's top face
  double dx = 0, dy = 0, dz = 0;
  bool periodic_y = false;  // the y sides one seam: row ny - 1 is row 0 (period (ny - 1) dy)

  std::size_t index(std::size_t i, std::size_t j, std::size_t k) const {
    return i + nx * (j + ny * k);
  }
  std::size_t size() const { return nx * ny * nz; }
  double x(std::size_t i) const { return x0 + dx * static_cast<double>(i); }
  double y(std::size_t j) const { return y0 + dy * static_cast<double>(j); }
  // The plate's top plane (the bed's floor).
  std::size_t k_plate() const { return nz - 1 - nz_above; }
  double z(std::size_t k) const {
    return z_top + dz * (static_cast<double>(k) - static_cast<double>(k_plate()));
  }
  std::size_t columns() const { return nx * ny; }
  // The node of column i + nx j in plane k.
  std::size_t node(std::size_t column, std::size_t k) const { return column + columns() * k; }
  bool fixed(std::size_t i, std::size_t j, std::size_t k) const {
    return i == 0 || k == 0 || i + 1 == nx || (!periodic_y && (j == 0 || j + 1 == ny));
  }
  // Whether column i + nx j is a Dirichlet column (on the sides).
  bool fixed_column(std::size_t column) const {
    const std::size_t i = column % nx, j = column / nx;
    return i == 0 || i + 1 == nx || (!periodic_y && (j == 0 || j + 1 == ny));
  }
  // Whether column i + nx j is the image of row 0 across a periodic seam (neither free nor
  // fixed: a copy), and the column it copies (the column itself when it is no image).
  bool image_column(std::size_t column) const { return periodic_y && column / nx + 1 == ny; }
  std::size_t canonical_column(std::size_t column) const {
    return image_column(column) ? column - nx * (ny - 1) : column;
  }
  // The free rows are first_row() .. ny - 2; the row before row j (across the seam for row 0).
  std::size_t first_row() const { return periodic_y ? 0 : 1; }
  std::size_t row_before(std::size_t j) const { return j == 0 ? ny - 2 : j - 1; }
  // Row index j counted on past the seam (below 0 or beyond ny - 2), wrapped into the period
  // (the rows as a periodic HeightMap's nodes: the last is the first).
  std::size_t wrap_row(long j) const { return bed::HeightMap::wrap_index(j, ny); }
  // The seam's period across y: the plate's width, row ny - 1 being row 0 again.
  double period_y() const { return dy * static_cast<double>(ny - 1); }
  // Volume of a whole cell; a column's top node owns a share of it (Sinter's thickness).
  double cell_volume() const { return dx * dy * dz; }
};

// The four columns (i + nx j) around (x, y) with bilinear weights (summing to 1): how a
// particle contact is spread over the grid cell under it, onto those columns' top nodes.
struct TopStencil {
  std::size_t column[4];
  double weight[4];
};
TopStencil top_stencil(const SubstrateGeometry& g, double x, double y);

// The columns whose (x, y) lie within a disc of radius a centred over (x, y), equally weighted
// (their cells are equal), or the bilinear corners when the disc covers no node: what a spread
// cap touches (wetting) and where a fused particle's volume goes (fusion). Weights sum to 1.
std::vector<std::pair<std::size_t, double>> top_footprint(const SubstrateGeometry& g, double x,
                                                          double y, double a);

// The columns x_i of a single track's steady part, where sections are measured (MeltPoolAlong,
// Bead): i from nx/4 to 3(nx - 1)/4, the grid's middle half, away from the beam's switching on
// and off.
inline std::pair<std::size_t, std::size_t> steady_columns(const SubstrateGeometry& g) {
  return {g.nx / 4, 3 * (g.nx - 1) / 4};
}

// The solid's top surface over the grid: per column i + nx j the height z of the solid there, at
// or above the plate's top face z_top (fusion raises it); empty: flat at z_top. The column's
// nodes up to the height are solid (SubstrateGeometry; docs/sinter.md "Fusion").
using TopHeight = std::vector<double>;
// The top at (x, y), bilinear in the column heights.
double top_height_at(const SubstrateGeometry& g, const TopHeight& top, double x, double y);
// The same surface as a height map over the top face's nodes (empty when `top` is: the flat
// plate), for the spreading run's floor (dem/spread.hpp SpreadSettings::floor).
bed::HeightMap top_surface(const SubstrateGeometry& g, const TopHeight& top);

}  // namespace powderbed::thermal
