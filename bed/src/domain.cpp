#include "powderbed/bed/domain.hpp"

#include <cmath>
#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

void Domain::validate(const char* what) const {
  if (dimension != 2 && dimension != 3) {
    throw InputError(fmt::format("{}: dimension is {} (accepted: 2 or 3)", what, dimension));
  }
  for (int a = 0; a < dimension; ++a) {
    if (!std::isfinite(lower[a]) || !std::isfinite(upper[a]) || !(upper[a] > lower[a])) {
      throw InputError(fmt::format("{}: domain axis {} is [{:g}, {:g}] (accepted: finite with "
                                   "lower < upper)",
                                   what, "xyz"[a], lower[a], upper[a]));
    }
  }
}

}  // namespace powderbed::bed
