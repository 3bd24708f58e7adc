#pragma once
// The melt pool as [GZ] measure it (docs/physics.md §5): on the plane x = x_plane, the region that ever
// reached T_m. Substrate: nodes of the grid plane nearest x_plane; depth below the plate's top face
// and width along the columns' top nodes, each edge placed by linear interpolation of the peak temperature
// between the last node at or above T_m and the next one. Particles: those the plane cuts (their
// circle of radius sqrt(r^2 - (x - x_plane)^2)) with a peak temperature at or above T_m; the
// height is the highest top of such a circle above the substrate. Width spans both.
#include <cstdint>
#include <vector>

#include "powderbed/thermal/solver.hpp"
#include "powderbed/thermal/substrate.hpp"

namespace powderbed::thermal {

// Where between two nodes (a molten, b not) the peak temperature crosses t_m, as a fraction of
// the spacing from a (0 when a is not the hotter).
double crossing(double peak_a, double peak_b, double t_m);

struct MeltPoolInput {
  const SubstrateGeometry* grid;
  const std::vector<double>* node_peak;  // peak temperature per node
  const std::vector<std::uint32_t>* top_plane;  // per column, its top node's plane
  const std::vector<double>* x, *y, *z, *radius, *particle_peak;
  double melting_point;
  double x_plane;
};

MeltPool measure_melt_pool(const MeltPoolInput& in);

// The same measure on the vertical plane through (cx, cy) across the unit direction (dx, dy) of
// a track of any heading: the columns nearest the plane, in order along it (columns[q]: the
// column i + nx j, its position projected on the plane at across[q] m from (cx, cy),
// increasing), with the peak temperatures of their nodes (peak[q nz + k]); particles cut by the
// plane. Edges are interpolated between neighbouring columns' top nodes as on a grid line. The
// depth is measured from each column's top (a molten top node is molten through it).
struct SectionInput {
  const SubstrateGeometry* grid;
  const std::vector<std::size_t>* columns;
  const std::vector<double>* across;
  const std::vector<double>* peak;
  const std::vector<std::uint32_t>* top_plane;  // per column, its top node's plane
  const std::vector<double>* x, *y, *z, *radius, *particle_peak;
  double melting_point;
  double cx, cy, dx, dy;
  const TopHeight* top;  // a raised top: depth from each column's own top (empty: flat)
};

MeltPool measure_section(const SectionInput& in);

}  // namespace powderbed::thermal
