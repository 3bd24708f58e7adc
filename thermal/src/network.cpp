#include "powderbed/thermal/network.hpp"

#include "powderbed/bed/neighbours.hpp"
#include "powderbed/thermal/contact_conduction.hpp"

namespace powderbed::thermal {

ConductionNetwork build_network(const bed::Bed& bed, const SubstrateGeometry& grid,
                                const TopHeight& top) {
  ConductionNetwork net;
  const std::size_t n = bed.n();
  std::vector<std::uint8_t> touched(n, 0);
  if (n > 1) {
    bed::Bed open = bed;
    open.domain.periodic = {false, false, false};
    for (const auto& p : bed::neighbour_pairs_cell_list(open, 0.0)) {
      const double a = contact_radius(bed.radius[p.i], bed.radius[p.j], p.distance);
      if (a <= 0 || p.distance <= 0) continue;
      net.pairs.push_back({p.i, p.j, conduction_shape_factor(a, p.distance)});
      touched[p.i] = touched[p.j] = 1;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    double h = bed.z[i] - top_height_at(grid, top, bed.x[i], bed.y[i]);
    // A centre at or below a raised top (a powder particle beside a fused one, whose volume
    // fusion spread over its footprint) meets the solid as if sunk to half its radius.
    if (h <= 0) h = 0.5 * bed.radius[i];
    const double a = plane_contact_radius(bed.radius[i], h);
    if (a <= 0) continue;
    net.substrate.push_back({static_cast<std::uint32_t>(i), conduction_shape_factor(a, h),
                             top_stencil(grid, bed.x[i], bed.y[i])});
    touched[i] = 1;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!touched[i]) net.isolated.push_back(static_cast<std::uint32_t>(i));
  return net;
}

}  // namespace powderbed::thermal
