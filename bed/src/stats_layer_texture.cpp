// Surface texture of a height map (ISO 25178-2 areal parameters, docs/spread-layer.md "Sa, Sq"):
//   mean = (1/N) sum h_k,  Sa = (1/N) sum |h_k - mean|,  Sq = sqrt((1/N) sum (h_k - mean)^2),
// over all N cells (bare plate at h = 0 included: a gap in the layer is its roughest feature),
// and coverage = (cells with powder over their centre) / N.
#include <cmath>

#include "powderbed/bed/stats_layer.hpp"

namespace powderbed::bed {

SurfaceTexture surface_texture(const LayerHeightMap& map) {
  SurfaceTexture t;
  const std::size_t n = map.height.size();
  if (n == 0) return t;
  const double count = static_cast<double>(n);
  double sum = 0, covered = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sum += map.height[k];
    covered += map.covered[k] ? 1.0 : 0.0;
  }
  t.mean = sum / count;
  t.coverage = covered / count;
  double abs_dev = 0, sq_dev = 0;
  for (const double h : map.height) {
    abs_dev += std::abs(h - t.mean);
    sq_dev += (h - t.mean) * (h - t.mean);
  }
  t.sa = abs_dev / count;
  t.sq = std::sqrt(sq_dev / count);
  return t;
}

}  // namespace powderbed::bed
