// The height map of a spread layer as CSV (docs/spread-layer.md "Height map"), the input of
// scripts/plot_height_map.py: one row per cell, x fastest, full precision, written atomically.
#include <cstdio>

#include "io_detail.hpp"
#include "powderbed/bed/stats_layer.hpp"

namespace powderbed::bed {

void write_height_map_csv(const LayerHeightMap& map, const std::string& path) {
  detail::AtomicFile file(path);
  std::string text = "x,y,height,covered\n";
  text.reserve(text.size() + map.height.size() * 64);
  char line[128];
  for (std::size_t iy = 0; iy < map.ny; ++iy) {
    const double y = map.y0 + (static_cast<double>(iy) + 0.5) * map.dy;
    for (std::size_t ix = 0; ix < map.nx; ++ix) {
      const std::size_t k = iy * map.nx + ix;
      const double x = map.x0 + (static_cast<double>(ix) + 0.5) * map.dx;
      // %.17g: every value reads back bit for bit.
      const int len = std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%d\n", x, y,
                                    map.height[k], map.covered[k] ? 1 : 0);
      text.append(line, static_cast<std::size_t>(len));
    }
  }
  detail::write_text(file.temp_path(), path, text);
  file.commit();
}

}  // namespace powderbed::bed
