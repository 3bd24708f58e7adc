#pragma once
// The progress bar of long runs (README "The programs": progress with an ETA on
// stderr when stderr is a terminal): "[#####.....]  45 %  <detail>  ETA 12 s", redrawn in place.
#include <chrono>
#include <string>

namespace powderbed::app {

class ProgressBar {
 public:
  // Draws `fraction` (0..1) done with the program's own `detail`; the ETA extrapolates the wall
  // time since construction. A newline follows the bar once the fraction reaches 1.
  void draw(double fraction, const std::string& detail) const;

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace powderbed::app
