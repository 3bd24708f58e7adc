#pragma once
// The bead a track leaves: how high the fused solid stands over the plate's top face on the
// track's cross-sections, as a user measures a bead in polished sections. On each grid column
// x_i of the track's steady part (steady_columns, as MeltPoolAlong) the bead's height is the
// highest column of that section above z_top; the plane x = Lx/2 is the column nearest it (the
// melt pool's plane). Without levelling (fuse's L = 0)
// the solid keeps a spike over each fused particle and the height is the tallest spike's: a
// bead is levelled by capillarity before it freezes (fusion.hpp), which sinter --fuse.level
// stands in for.
#include <cstddef>

#include "powderbed/thermal/substrate.hpp"

namespace powderbed::thermal {

struct Bead {
  double height = 0;                       // on the plane x = Lx/2, m
  std::size_t sections = 0;                // columns x_i of the steady part
  double height_mean = 0, height_sd = 0;   // over them, m
};

// `top` empty (nothing fused, the flat plate): a bead of height 0.
Bead measure_bead(const SubstrateGeometry& g, const TopHeight& top);

}  // namespace powderbed::thermal
