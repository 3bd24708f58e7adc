// The DEM run's subnormal flush (dem/src/flush_subnormals.hpp): on inside the guard, in every
// thread of the engine's OpenMP loops, and the caller's mode back after it.
#include <gtest/gtest.h>

#include <cfloat>
#include <vector>

#include "flush_subnormals.hpp"
#include "parallel.hpp"

namespace {

// DBL_MIN / 4 is subnormal; `volatile` keeps the compiler from folding the product.
double quarter_of_smallest_normal() {
  volatile double smallest = DBL_MIN;
  volatile double quarter = 0.25;
  return smallest * quarter;
}

TEST(FlushSubnormals, OnInsideTheGuardAndOffAfterIt) {
#if defined(__SSE2__)
  EXPECT_GT(quarter_of_smallest_normal(), 0.0);  // IEEE: gradual underflow
  {
    const powderbed::dem::detail::FlushSubnormals flush;
    EXPECT_EQ(quarter_of_smallest_normal(), 0.0);
  }
  EXPECT_GT(quarter_of_smallest_normal(), 0.0);  // the caller's mode restored
#else
  GTEST_SKIP() << "the flush is x86 (SSE2) only";
#endif
}

TEST(FlushSubnormals, OnInEveryThreadOfTheEnginesLoops) {
#if defined(__SSE2__)
  std::vector<double> product(64, -1.0);
  powderbed::dem::detail::for_each_particle(product.size(), 2, [&](std::size_t i) {
    product[i] = quarter_of_smallest_normal();
  });
  for (double p : product) EXPECT_EQ(p, 0.0);
  std::vector<double> chunked(64, -1.0);
  powderbed::dem::detail::for_each_chunk(chunked.size(), 2, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) chunked[i] = quarter_of_smallest_normal();
  });
  for (double p : chunked) EXPECT_EQ(p, 0.0);
  EXPECT_GT(quarter_of_smallest_normal(), 0.0);  // the calling thread untouched
#else
  GTEST_SKIP() << "the flush is x86 (SSE2) only";
#endif
}

}  // namespace
