#pragma once
// The Beer–Lambert beam's power on each particle it reaches (docs/physics.md §5): one loop for
// the explicit step, the implicit step and the absorbed fraction, so that all three skip the
// vaporised particles and cut the beam at the same radius (kBeamCutoff2).
#include <cstddef>

#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

// add(i, H_i) for every particle i not gone within the cut-off of the beam axis at (x, y), H_i
// its absorbed power under a beam of peak intensity i0 (W/m^2).
template <class Add>
void for_each_lit_particle(const Sinter::State& s, double x, double y, double i0, Add&& add) {
  const double w2 = s.laser.spot_radius * s.laser.spot_radius;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const double dx = s.x[i] - x, dy = s.y[i] - y;
    const double r2 = dx * dx + dy * dy;
    if (r2 > kBeamCutoff2 * w2 || s.gone[i]) continue;
    add(i, particle_laser_power(s.laser_factor[i], i0, r2, w2));
  }
}

}  // namespace powderbed::thermal
