#pragma once
// The dosing platform of a spread (SpreadSettings::platform_edge; docs/deposit-spread.md "The
// dosing platform"): a machine doses each layer's powder in front of the recoater on a fixed
// table flush with the recoater's bottom, beside the build chamber whose plate goes down a layer
// at a time (the working plane of a dosing-piston machine). The spread keeps the plate's frame,
// so the table rises with the tool: the floor under x <= edge stands at the tool's bottom, and
// the supply's heap rests on it, not on the earlier layers' powder. Without it that powder,
// pressed by the heap, moves and cannot sleep (docs/results/build-ab-layer3.md).
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "box.hpp"
#include "powderbed/bed/height_map.hpp"

namespace powderbed::dem::detail {

// The floor a layer spreads on: `solid` (the fused part; empty: the flat plate, then on a grid of
// about an eighth of the tool's `gap` over the box) with every node at x <= edge raised to `top`.
// Between the last node on the platform and the next the floor falls in one cell: the platform's
// edge, as steep as the grid allows (8 : 1 on the layer's scale on the plate's own grid).
inline bed::HeightMap with_platform(const bed::HeightMap& solid, const Box& box, double edge, double top,
                                    double gap) {
  bed::HeightMap floor = solid;
  if (floor.empty()) {
    const double spacing = gap / 8;
    const auto nodes = [&](int a) {
      return static_cast<std::size_t>(std::ceil(box.length[a] / spacing - 1e-9)) + 1;
    };
    floor.nx = nodes(0);
    floor.ny = nodes(1);
    floor.x0 = box.lower[0];
    floor.y0 = box.lower[1];
    floor.dx = box.length[0] / static_cast<double>(floor.nx - 1);
    floor.dy = box.length[1] / static_cast<double>(floor.ny - 1);
    floor.z.assign(floor.nx * floor.ny, box.lower[2]);
  }
  for (std::size_t j = 0; j < floor.ny; ++j) {
    for (std::size_t i = 0; i < floor.nx && floor.x0 + floor.dx * static_cast<double>(i) <= edge; ++i) {
      double& h = floor.z[i + floor.nx * j];
      h = std::max(h, top);
    }
  }
  return floor;
}

}  // namespace powderbed::dem::detail
