// The image row of a periodic seam (SubstrateGeometry::periodic_y): row ny - 1 is row 0 seen
// across the seam. Row ny - 2 reads it as its neighbour, the tracer and the melt-pool measures
// read it as the surface there, so it holds row 0's state; nothing is ever booked to it
// (deposits go to row 0: canonical_column), so copying loses no energy.
#include <algorithm>

#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

template <typename T>
void copy_row(const SubstrateGeometry& g, std::vector<T>& field, std::size_t plane) {
  const auto from = field.begin() + static_cast<std::ptrdiff_t>(g.node(0, plane));
  std::copy_n(from, g.nx, from + static_cast<std::ptrdiff_t>(g.nx * (g.ny - 1)));
}

}  // namespace

void copy_image_row(Sinter::State& s) {
  const SubstrateGeometry& g = s.g;
  if (!g.periodic_y) return;
  for (std::size_t k = 0; k < g.nz; ++k) {
    copy_row(g, s.e, k);
    copy_row(g, s.node_temperature, k);
    copy_row(g, s.node_k, k);
    copy_row(g, s.node_peak, k);
  }
  copy_row(g, s.top_plane, 0);
  copy_row(g, s.top_thickness, 0);
  copy_row(g, s.transmission, 0);
  if (!s.top.empty()) copy_row(g, s.top, 0);
}

}  // namespace powderbed::thermal
