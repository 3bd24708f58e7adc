#include "powderbed/thermal/bead.hpp"

#include <algorithm>
#include <cmath>

#include "powderbed/bed/moments.hpp"

namespace powderbed::thermal {

namespace {

// The section's height: its highest column above the plate's top face.
double section_height(const SubstrateGeometry& g, const TopHeight& top, std::size_t i) {
  double high = 0;
  for (std::size_t j = 0; j < g.ny; ++j) high = std::max(high, top[i + g.nx * j] - g.z_top);
  return high;
}

}  // namespace

Bead measure_bead(const SubstrateGeometry& g, const TopHeight& top) {
  Bead b;
  if (top.empty()) return b;
  const double middle = 0.5 * static_cast<double>(g.nx - 1);  // the column of x = Lx/2
  b.height = section_height(g, top, static_cast<std::size_t>(std::lround(middle)));
  bed::Moments heights;
  const auto [first, last] = steady_columns(g);
  for (std::size_t i = first; i <= last; ++i) heights.add(section_height(g, top, i));
  b.sections = heights.n;
  b.height_mean = heights.mean();
  b.height_sd = heights.sd();
  return b;
}

}  // namespace powderbed::thermal
