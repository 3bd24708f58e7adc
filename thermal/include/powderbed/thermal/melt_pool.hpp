#pragma once
// The melt pool as [GZ] measure it (SPEC.md §5): on the plane x = x_plane, the region that ever
// reached T_m. Substrate: nodes of the grid plane nearest x_plane; depth below the top face and
// width along the top row, each edge placed by linear interpolation of the peak temperature
// between the last node at or above T_m and the next one. Particles: those the plane cuts (their
// circle of radius sqrt(r^2 - (x - x_plane)^2)) with a peak temperature at or above T_m; the
// height is the highest top of such a circle above the substrate. Width spans both.
#include <vector>

#include "powderbed/thermal/solver.hpp"
#include "powderbed/thermal/substrate.hpp"

namespace powderbed::thermal {

struct MeltPoolInput {
  const SubstrateGeometry* grid;
  const std::vector<double>* node_peak;  // peak temperature per node
  const std::vector<double>* x, *y, *z, *radius, *particle_peak;
  double melting_point;
  double x_plane;
};

MeltPool measure_melt_pool(const MeltPoolInput& in);

// The same measure on the vertical plane through (cx, cy) across the unit direction (dx, dy) of
// a track of any heading: its top-face columns sampled along the plane at spacing `step`
// (columns[q]: the top-face index i + nx j nearest sample q, at `across[q]` m along the plane),
// with the peak temperatures of their nodes (peak[q nz + k]); particles cut by the plane. The
// depth is measured from each column's top (a raised top lumps its solid into the top node: a
// molten top node is molten through it).
struct SectionInput {
  const SubstrateGeometry* grid;
  const std::vector<std::size_t>* columns;
  const std::vector<double>* across;
  double step;
  const std::vector<double>* peak;
  const std::vector<double>* x, *y, *z, *radius, *particle_peak;
  double melting_point;
  double cx, cy, dx, dy;
  const TopHeight* top;  // a raised top: depth from each column's own top (empty: flat)
};

MeltPool measure_section(const SectionInput& in);

}  // namespace powderbed::thermal
