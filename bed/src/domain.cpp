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

Domain box_of_lengths(const std::vector<double>& lengths, const char* what) {
  if (lengths.size() != 2 && lengths.size() != 3)
    throw InputError(fmt::format("{}: {} lengths (accepted: LX,LY or LX,LY,LZ in m)", what, lengths.size()));
  Domain d;
  d.dimension = static_cast<int>(lengths.size());
  d.upper = {lengths[0], lengths[1], d.dimension == 3 ? lengths[2] : 0.0};
  d.validate(what);
  return d;
}

}  // namespace powderbed::bed
