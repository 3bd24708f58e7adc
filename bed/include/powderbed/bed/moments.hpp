#pragma once
// The mean and the population standard deviation of values taken one at a time, from their
// sum and sum of squares: sd = √(max(0, Σv²/n − mean²)) (the max keeps round-off from making
// the variance of equal values negative). One pass, for the few hundred values of a report
// (a bed's radii, a track's sections), where cancellation is far below the digits printed.
#include <algorithm>
#include <cmath>
#include <cstddef>

namespace powderbed::bed {

struct Moments {
  double sum = 0, squares = 0;
  std::size_t n = 0;

  void add(double v) {
    sum += v;
    squares += v * v;
    ++n;
  }
  double mean() const { return n ? sum / static_cast<double>(n) : 0.0; }
  double sd() const {
    if (!n) return 0.0;
    const double m = mean();
    return std::sqrt(std::max(0.0, squares / static_cast<double>(n) - m * m));
  }
};

}  // namespace powderbed::bed
