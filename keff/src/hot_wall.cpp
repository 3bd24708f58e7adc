// hot_wall.hpp: the hot wall below the powder's solidus.
#include "powderbed/keff/hot_wall.hpp"

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"

namespace powderbed::keff {

void check_hot_wall(double hot, const bed::MaterialFile* material, bool trust_units) {
  if (!material) {
    constexpr double kTungstenMelts = 3695;  // K
    if (hot > kTungstenMelts && !trust_units)
      throw InputError(fmt::format("--t-hot: the hot wall at {:g} K is above any metal's melting "
                                   "point (tungsten: 3695 K) (accepted: a solid bed; --material "
                                   "bounds it by the material's solidus; --trust-units if meant)",
                                   hot));
    return;
  }
  const bool solidus = material->get("solidus").has_value();
  const auto solid_until = solidus ? material->get("solidus") : material->get("melting_point");
  if (solid_until && !(hot < *solid_until)) {
    throw InputError(fmt::format("--t-hot: the hot wall at {:g} K is not below {}'s {} {:g} K (accepted: a solid "
                                 "bed, T_hot < {:g} K)",
                                 hot, material->name, solidus ? "solidus" : "melting point", *solid_until,
                                 *solid_until));
  }
}

}  // namespace powderbed::keff
