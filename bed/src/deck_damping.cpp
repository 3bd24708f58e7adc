// zeta -> LAMMPS / LIGGGHTS damping inputs (deck_damping.hpp).
#include "powderbed/bed/deck_damping.hpp"

#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

double tsuji_alpha(double e) {
  // Horner form of the sixth-degree fit (coefficients of the LAMMPS pair granular docs).
  return 1.2728 + e * (-4.2783 + e * (11.087 + e * (-22.348 + e * (27.467 + e * (-18.022 + e * 4.8218)))));
}

double lammps_tsuji_max_zeta(bool hertz) {
  return tsuji_alpha(0.0) / (hertz ? std::sqrt(6.0) : 2.0);
}

double lammps_tsuji_input(double zeta, bool hertz, const char* option) {
  const double alpha = zeta * (hertz ? std::sqrt(6.0) : 2.0);
  if (!(alpha <= tsuji_alpha(0.0)) || !(alpha >= tsuji_alpha(1.0))) {
    throw InputError(fmt::format(
        "{}: zeta {:g} has no LAMMPS damping tsuji input (accepted: {:g} <= zeta <= {:g} for the "
        "{} law, or 0)",
        option, zeta, tsuji_alpha(1.0) / (hertz ? std::sqrt(6.0) : 2.0),
        lammps_tsuji_max_zeta(hertz), hertz ? "Hertz" : "linear"));
  }
  // alpha(e) decreases monotonically on [0, 1]: bisection to the last bit.
  double lo = 0, hi = 1;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (tsuji_alpha(mid) > alpha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double liggghts_hertz_restitution(double zeta, const char* option) {
  const double b = zeta / std::sqrt(5.0 / 6.0);
  if (!(b >= 0) || !(b < 1)) {
    throw InputError(fmt::format(
        "{}: zeta {:g} has no LIGGGHTS coefficientRestitution (accepted: 0 <= zeta < sqrt(5/6) = "
        "0.9129)",
        option, zeta));
  }
  return std::exp(-std::numbers::pi * b / std::sqrt(1 - b * b));
}

}  // namespace powderbed::bed
