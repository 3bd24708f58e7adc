#pragma once
// Loops over particles: OpenMP with a static schedule when threads > 1, a plain loop otherwise
// (a team of one still pays libgomp's fork and barrier, microseconds per loop, which dominated
// small beds). Each iteration writes only its own particle, so results do not depend on the
// thread count; the reductions are max and min, which are exact in any order. Each region flushes
// subnormals in each of its threads, as the run's own thread does (flush_subnormals.hpp).
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include <omp.h>

#include "flush_subnormals.hpp"

namespace powderbed::dem::detail {

template <class F>
void for_each_particle(std::size_t n, int threads, F&& body) {
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) body(i);
    return;
  }
  const long long count = static_cast<long long>(n);
#pragma omp parallel num_threads(threads)
  {
    const FlushSubnormals flush;
#pragma omp for schedule(static)
    for (long long i = 0; i < count; ++i) body(static_cast<std::size_t>(i));
  }
}

// body(begin, end) over contiguous chunks of [0, n), one per thread (the whole range when
// threads <= 1): for loops written as plain functions with restrict-qualified arrays, which the
// compiler vectorises (it gives up on the runtime alias checks of a lambda over many arrays).
template <class F>
void for_each_chunk(std::size_t n, int threads, F&& body) {
  if (threads <= 1) {
    body(std::size_t{0}, n);
    return;
  }
#pragma omp parallel num_threads(threads)
  {
    const FlushSubnormals flush;
    const auto team = static_cast<std::size_t>(omp_get_num_threads());
    const auto rank = static_cast<std::size_t>(omp_get_thread_num());
    body(n * rank / team, n * (rank + 1) / team);
  }
}

// for_each_chunk for a body that returns bits (a test for non-finite values): their OR over
// the chunks, which is exact in any order.
template <class F>
std::uint64_t or_over_chunks(std::size_t n, int threads, F&& body) {
  if (threads <= 1) return body(std::size_t{0}, n);
  std::uint64_t bits = 0;
#pragma omp parallel num_threads(threads) reduction(| : bits)
  {
    const FlushSubnormals flush;
    const auto team = static_cast<std::size_t>(omp_get_num_threads());
    const auto rank = static_cast<std::size_t>(omp_get_thread_num());
    bits |= body(n * rank / team, n * (rank + 1) / team);
  }
  return bits;
}

}  // namespace powderbed::dem::detail
