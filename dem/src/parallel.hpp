#pragma once
// Loops over particles: OpenMP with a static schedule when threads > 1, a plain loop otherwise
// (a team of one still pays libgomp's fork and barrier, microseconds per loop, which dominated
// small beds). Each iteration writes only its own particle, so results do not depend on the
// thread count; the reductions are max and min, which are exact in any order.
#include <algorithm>
#include <cstddef>

namespace powderbed::dem::detail {

template <class F>
void for_each_particle(std::size_t n, int threads, F&& body) {
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) body(i);
    return;
  }
  const long long count = static_cast<long long>(n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long long i = 0; i < count; ++i) body(static_cast<std::size_t>(i));
}

// max over particles of value(i) (>= 0).
template <class F>
double max_over_particles(std::size_t n, int threads, F&& value) {
  double worst = 0;
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, value(i));
    return worst;
  }
  const long long count = static_cast<long long>(n);
#pragma omp parallel for schedule(static) num_threads(threads) reduction(max : worst)
  for (long long i = 0; i < count; ++i) worst = std::max(worst, value(static_cast<std::size_t>(i)));
  return worst;
}

}  // namespace powderbed::dem::detail
