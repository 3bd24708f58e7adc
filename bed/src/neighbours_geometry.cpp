// Shared pair geometry of the neighbour searches (wrapped centres, minimum image).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "neighbours_detail.hpp"
#include "powderbed/bed/errors.hpp"

namespace powderbed::bed::detail {

namespace {

// Wraps v into [lo, lo + length); values already inside are returned unchanged (bit for bit).
double wrap(double v, double lo, double length) {
  const double hi = lo + length;
  if (v >= lo && v < hi) return v;
  double w = v - length * std::floor((v - lo) / length);
  if (w >= hi || w < lo) w = lo;  // rounding put it on the far face: same point periodically
  return w;
}

void check_finite(const std::vector<double>& v, const char* name) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw InputError(fmt::format("neighbour search: {}[{}] is {:g} (accepted: finite numbers)",
                                   name, i, v[i]));
    }
  }
}

}  // namespace

PairGeometry::PairGeometry(const Bed& bed) : dim(bed.domain.dimension) {
  bed.domain.validate("neighbour search");
  const std::size_t n = bed.n();
  if (bed.x.size() != n || bed.y.size() != n || bed.z.size() != n) {
    throw InputError(fmt::format(
        "neighbour search: position arrays have {}, {}, {} entries for {} radii (accepted: one "
        "per particle)",
        bed.x.size(), bed.y.size(), bed.z.size(), n));
  }
  check_finite(bed.x, "position x");
  check_finite(bed.y, "position y");
  check_finite(bed.z, "position z");
  check_finite(bed.radius, "radius");
  for (int a = 0; a < 3; ++a) {
    periodic[a] = a < dim && bed.domain.periodic[a];
    lower[a] = bed.domain.lower[a];
    length[a] = a < dim ? bed.domain.length(a) : 0.0;
    half[a] = 0.5 * length[a];
  }
  const std::vector<double>* in[3] = {&bed.x, &bed.y, &bed.z};
  std::vector<double>* out[3] = {&x, &y, &z};
  for (int a = 0; a < 3; ++a) {
    *out[a] = *in[a];
    if (!periodic[a]) continue;
    for (double& v : *out[a]) v = wrap(v, bed.domain.lower[a], length[a]);
  }
}

void check_pair_index_range(const Bed& bed, const char* what) {
  if (bed.n() >= std::numeric_limits<std::uint32_t>::max()) {
    throw InputError(
        fmt::format("{}: bed has {} particles (accepted: fewer than 2^32)", what, bed.n()));
  }
}

void check_number(double value, const char* what, bool positive) {
  if (!std::isfinite(value) || (positive && !(value > 0))) {
    throw InputError(fmt::format("{} is {:g}{}", what, value,
                                 positive ? " (accepted: > 0, finite)" : " (accepted: finite)"));
  }
}

double max_radius(const Bed& bed) {
  return bed.radius.empty() ? 0.0 : *std::max_element(bed.radius.begin(), bed.radius.end());
}

void sort_pairs(std::vector<NeighbourPair>& pairs, std::size_t n) {
  std::vector<std::size_t> start(n + 1, 0);
  for (const auto& p : pairs) ++start[p.i + 1];
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<NeighbourPair> sorted(pairs.size());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (const auto& p : pairs) sorted[fill[p.i]++] = p;
  for (std::size_t i = 0; i < n; ++i) {
    std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(start[i]),
              sorted.begin() + static_cast<std::ptrdiff_t>(start[i + 1]),
              [](const NeighbourPair& a, const NeighbourPair& b) { return a.j < b.j; });
  }
  pairs.swap(sorted);
}

}  // namespace powderbed::bed::detail
