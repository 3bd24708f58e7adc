#pragma once
// When a bed is at rest: a drop's --until-rest (solver.hpp) and a spread layer's settle to rest
// (spread.hpp).

namespace powderbed::dem {

// The bed is at rest when, at every check during `window` seconds of simulated time, the
// largest speed is below max_speed and the kinetic energy below kinetic_energy (a spread's
// layer tests the speed of the powder behind the tool alone).
struct RestCriteria {
  double max_speed = 1e-4;        // m/s
  double kinetic_energy = 0;      // J; 0 means 1e-2 * (1/2) M max_speed^2 (M the bed's mass),
                                  // i.e. an RMS speed of 10 % of max_speed
  double window = 1e-3;           // s
};

}  // namespace powderbed::dem
