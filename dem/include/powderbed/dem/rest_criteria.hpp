#pragma once
// When a bed is at rest: a drop's --until-rest (solver.hpp) and a spread layer's settle to rest
// (spread.hpp), both judged by one RestWatch.

#include <algorithm>
#include <cmath>
#include <cstdint>

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

// The rest test over time: checks about ten a window (at most every 100 steps, never every
// step, as the speeds cost a pass over the bed), and rest once every check from the first quiet
// one to a window later found the bed quiet. The window counts from that first quiet check, not
// from the check before it: what happened between the two is not known.
class RestWatch {
 public:
  RestWatch(const RestCriteria& rest, double dt)
      : every_(static_cast<std::uint64_t>(std::clamp(std::floor(rest.window / dt / 10.0), 1.0, 100.0))),
        window_steps_(static_cast<std::uint64_t>(std::ceil(rest.window / dt))) {}

  // Steps between two checks.
  std::uint64_t every() const { return every_; }

  // One check at `step`: whether the bed is quiet now; true once it has been through the window.
  bool check(std::uint64_t step, bool quiet) {
    if (!quiet) {
      since_ = kNotQuiet;
      return false;
    }
    if (since_ == kNotQuiet) since_ = step;
    return step - since_ >= window_steps_;
  }

  // A new stretch: no check so far was quiet.
  void reset() { since_ = kNotQuiet; }

 private:
  static constexpr std::uint64_t kNotQuiet = ~std::uint64_t{0};
  std::uint64_t every_, window_steps_;
  std::uint64_t since_ = kNotQuiet;  // step of the first check of the current quiet stretch
};

}  // namespace powderbed::dem
