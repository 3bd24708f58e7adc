#pragma once
// The bed's conduction network (SPEC.md §5): particle pairs that overlap, with the shape factor
// A_ij / |x_j - x_i| of their contact, and particles that overlap the substrate's top face,
// with the shape factor A / h (h: centre height above the face) and the grid cell under them.
#include <cstdint>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/substrate.hpp"

namespace powderbed::thermal {

struct ContactPair {
  std::uint32_t i, j;
  double shape;  // π a^2 / d, m
};

struct SubstrateContact {
  std::uint32_t particle;
  double shape;  // π a^2 / h, m
  TopStencil stencil;
};

struct ConductionNetwork {
  std::vector<ContactPair> pairs;
  std::vector<SubstrateContact> substrate;
  std::vector<std::uint32_t> isolated;  // particles with no contact at all
};

// Periodic axes of the bed are ignored: the substrate has Dirichlet sides. A raised top (empty:
// flat) is met at its local height: h is the centre's height above it.
ConductionNetwork build_network(const bed::Bed& bed, const SubstrateGeometry& grid,
                                const TopHeight& top = {});

}  // namespace powderbed::thermal
