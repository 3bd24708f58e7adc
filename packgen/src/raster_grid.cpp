#include "powderbed/packgen/raster_grid.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"

namespace powderbed::packgen {

std::array<std::size_t, 3> RasterGrid::points(const bed::Domain& domain, double h) {
  std::array<std::size_t, 3> n{1, 1, 1};
  for (int a = 0; a < domain.dimension; ++a) {
    n[a] = static_cast<std::size_t>(std::floor(domain.length(a) / h)) + 1;
  }
  return n;
}

namespace {

double total_points(const bed::Domain& domain, double h) {
  double total = 1;  // in double: an absurdly fine h must not overflow size_t
  for (int a = 0; a < domain.dimension; ++a) total *= std::floor(domain.length(a) / h) + 1;
  return total;
}

}  // namespace

double RasterGrid::finest_spacing(const bed::Domain& domain, std::size_t max_bytes) {
  double h = std::pow(domain.measure() / static_cast<double>(max_bytes), 1.0 / domain.dimension);
  while (total_points(domain, h) > static_cast<double>(max_bytes)) h *= 1.001;
  return h;
}

RasterGrid::RasterGrid(const bed::Domain& domain, double h, const Particles& particles,
                       std::size_t max_bytes)
    : p_(particles), dimension_(domain.dimension), lower_(domain.lower), h_(h) {
  if (!(h > 0) || !std::isfinite(h)) {
    throw InputError(fmt::format("--raster-spacing: {:g} (accepted: a spacing > 0 in m)", h));
  }
  if (total_points(domain, h) > static_cast<double>(max_bytes)) {
    throw InputError(fmt::format(
        "--raster-spacing: {:g} needs {:g} GiB for the status grid (limit {:g} GiB; the finest "
        "allowed for this domain is {:g})",
        h, total_points(domain, h) / (1 << 30), static_cast<double>(max_bytes) / (1 << 30),
        finest_spacing(domain, max_bytes)));
  }
  n_ = points(domain, h);
  status_.assign(n_[0] * n_[1] * n_[2], 0);
}

template <class F>
bool RasterGrid::visit(double x, double y, double z, double r, F&& f) const {
  const double c[3] = {x, y, z};
  std::size_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int a = 0; a < dimension_; ++a) {
    const double top = static_cast<double>(n_[a] - 1);
    const double l = std::ceil((c[a] - r - lower_[a]) / h_);
    const double u = std::floor((c[a] + r - lower_[a]) / h_);
    if (u < 0 || l > top) return false;
    lo[a] = static_cast<std::size_t>(std::max(l, 0.0));
    hi[a] = static_cast<std::size_t>(std::min(u, top));
  }
  const double r2 = r * r;
  for (std::size_t k = lo[2]; k <= hi[2]; ++k) {
    const double dz = dimension_ == 3 ? lower_[2] + static_cast<double>(k) * h_ - z : 0.0;
    for (std::size_t j = lo[1]; j <= hi[1]; ++j) {
      const double dy = lower_[1] + static_cast<double>(j) * h_ - y;
      const std::size_t row = (k * n_[1] + j) * n_[0];
      for (std::size_t i = lo[0]; i <= hi[0]; ++i) {
        const double dx = lower_[0] + static_cast<double>(i) * h_ - x;
        if (f(row + i, dx * dx + dy * dy + dz * dz - r2)) return true;
      }
    }
  }
  return false;
}

void RasterGrid::insert(std::uint32_t i) {
  visit(p_.x[i], p_.y[i], p_.z[i], p_.r[i], [&](std::size_t index, double excess) {
    if (excess <= 0) status_[index] = 1;
    return false;
  });
}

bool RasterGrid::fits(double x, double y, double z, double r) const {
  return !visit(x, y, z, r, [&](std::size_t index, double excess) {
    return excess < 0 && status_[index] != 0;
  });
}

}  // namespace powderbed::packgen
