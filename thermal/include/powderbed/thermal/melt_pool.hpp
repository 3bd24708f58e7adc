#pragma once
// The melt pool as [GZ] measure it (docs/physics.md §5): on the plane x = x_plane, the region that ever
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

}  // namespace powderbed::thermal
