#pragma once
// Bonding after a scan (docs/sinter.md "Fusion"): a particle's melt joins the solid only where it
// met melt of the solid. A liquid droplet resting on solid that never melted wets it only as far
// as the solid is molten; on cold solid its contact line freezes at once (the liquid-solid
// interface of 316L melt on a plate at ~400 K sits near 1,000 K, far below the solidus), so the
// droplet solidifies as a separate ball: the balling of Tolochko et al. (Rapid Prototyping J. 10,
// 2004) and of Gu & Shen (Mater. Des. 30, 2009), and the "fused but not bonded" powder of a
// layer whose pool did not reach the layer below.
//
// Judged on the bed the scan ran on (it does not move during a scan): a particle whose peak
// temperature reached the fusion threshold is bonded when it rests on the solid (its lowest point
// within dz/2 of the solid's top, as finely as the grid resolves that surface) where a top-face
// node of its footprint (the nodes within its projected disc) reached the threshold too, or when
// it touches a bonded particle that melted (the conduction network's pairs: a cluster of molten
// particles in contact is one body of liquid; a vaporised one has gone and carries none). A particle that merged into the pool during the
// scan (wetting) is bonded: it merged only where the solid had melted.
#include <cstdint>
#include <vector>

#include "powderbed/thermal/solver.hpp"

namespace powderbed::thermal {

// Per particle of `bed`, the bed `sinter` ran on: 1 where it melted (peak >= threshold, or merged) and its melt
// connects to molten solid as above, 0 otherwise.
std::vector<std::uint8_t> bonded_melt(const bed::Bed& bed, const Sinter& sinter, double threshold);

}  // namespace powderbed::thermal
