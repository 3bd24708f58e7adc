#include "powderbed/bed/domain.hpp"

#include <cmath>
#include <sstream>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

void Domain::validate(const char* what) const {
  if (dimension != 2 && dimension != 3) {
    std::ostringstream msg;
    msg << what << ": dimension is " << dimension << " (accepted: 2 or 3)";
    throw InputError(msg.str());
  }
  for (int a = 0; a < dimension; ++a) {
    if (!std::isfinite(lower[a]) || !std::isfinite(upper[a]) || !(upper[a] > lower[a])) {
      std::ostringstream msg;
      msg << what << ": domain axis " << "xyz"[a] << " is [" << lower[a] << ", " << upper[a]
          << "] (accepted: finite with lower < upper)";
      throw InputError(msg.str());
    }
  }
}

}  // namespace powderbed::bed
