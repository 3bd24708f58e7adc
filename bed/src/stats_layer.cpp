// The spread layer's statistics (docs/spread-layer.md): which particles make the layer, its
// density between the plate and the layer top, and the pieces of stats_layer_*.cpp together.
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <type_traits>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/stats_layer.hpp"

namespace powderbed::bed {

namespace {

template <class T>
[[noreturn]] void refuse(const char* field, T value, const std::string& accepted) {
  // A double prints with 6 significant digits ({:g}, as the stream did), a count whole.
  if constexpr (std::is_floating_point_v<T>)
    throw InputError(fmt::format("layer_stats: {} {:g} (accepted: {})", field, value, accepted));
  else
    throw InputError(fmt::format("layer_stats: {} {} (accepted: {})", field, value, accepted));
}

void check_request(const Bed& bed, const LayerRequest& q) {
  const Domain& d = bed.domain;
  d.validate("layer_stats");
  if (d.dimension != 3) refuse("dimension", d.dimension, "3D beds: a spread layer has a top view");
  const std::string range =
      fmt::format("{:g} <= plate < {:g} m, the domain's z range", d.lower[2], d.upper[2]);
  if (!(q.plate >= d.lower[2] && q.plate < d.upper[2])) refuse("plate", q.plate, range);
  if (!(q.gap > 0) || !std::isfinite(q.gap)) refuse("gap", q.gap, "> 0 m, finite");
  const std::string window =
      fmt::format("{:g} <= x0 < x1 <= {:g} m, inside the domain", d.lower[0], d.upper[0]);
  if (!(q.x0 >= d.lower[0] && q.x0 < q.x1)) refuse("window x0", q.x0, window);
  if (!(q.x1 <= d.upper[0])) refuse("window x1", q.x1, window);
  if (!(q.raster > 0) || !std::isfinite(q.raster)) refuse("raster", q.raster, "> 0 m, finite");
  // The map is stored per cell: more than 1e8 cells (0.9 GB) is a unit slip, not a finer map.
  const double cells = std::ceil((q.x1 - q.x0) / q.raster) * std::ceil(d.length(1) / q.raster);
  if (!(cells <= 1e8)) refuse("raster", q.raster, "a cell size giving at most 1e8 cells");
  constexpr std::size_t kMaxBins = 1000000;  // as bedstat's other bin counts
  if (q.segregation_bins == 0 || q.segregation_bins > kMaxBins) {
    refuse("segregation bins", q.segregation_bins, "1 to 1000000");
  }
}

}  // namespace

LayerStats layer_stats(const Bed& bed, const LayerRequest& request) {
  check_request(bed, request);
  LayerStats s;
  s.request = request;
  const Domain& d = bed.domain;
  const double top = request.plate + request.gap;
  // The box of the layer: the window in x, the whole strip across, plate to top.
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double ylo = d.periodic[1] ? -inf : d.lower[1], yhi = d.periodic[1] ? inf : d.upper[1];
  const double volume = solid_volume_in_box(bed, {request.x0, ylo, request.plate},
                                            {request.x1, yhi, top});
  s.density = volume / ((request.x1 - request.x0) * d.length(1) * request.gap);

  std::vector<double> x;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    if (bed.z[i] >= request.plate && bed.z[i] <= top && bed.x[i] >= request.x0 &&
        bed.x[i] <= request.x1) {
      x.push_back(bed.x[i]);
      s.diameters.push_back(2.0 * bed.radius[i]);
    }
  }
  s.particles = x.size();
  s.map = height_map(bed, request);
  const SurfaceTexture t = surface_texture(s.map);
  s.coverage = t.coverage;
  s.mean_height = t.mean;
  s.sa = t.sa;
  s.sq = t.sq;
  s.segregation = size_segregation(x, s.diameters, request.x0, request.x1, request.segregation_bins);
  return s;
}

}  // namespace powderbed::bed
