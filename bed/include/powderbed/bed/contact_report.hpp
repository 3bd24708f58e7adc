#pragma once
// The contact tolerances every program reports (Z at 1e-6, 1e-3 and 1e-2) and the
// text of a tolerance as a JSON key ("1e-06", "0.001", "0.01").
#include <array>
#include <cstdio>
#include <string>

namespace powderbed::bed {

inline constexpr std::array<double, 3> kReportedTolerances = {1e-6, 1e-3, 1e-2};

inline std::string tolerance_key(double tol) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", tol);
  return buf;
}

}  // namespace powderbed::bed
