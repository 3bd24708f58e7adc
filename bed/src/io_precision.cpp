// Is a text bed printed precisely enough for contact statistics? (docs/decks.md: a dump at
// LAMMPS's default 6 digits moves gaps of 1e-6 of a radius by far more than that.)
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

std::string printed_precision_warning(const Bed& bed, double tolerance) {
  const int digits = bed.provenance.printed_digits;
  if (digits <= 0 || digits >= 17 || bed.n() == 0) return "";  // binary, or exact doubles
  double max_centre = 0, max_radius = 0;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    max_centre = std::max({max_centre, std::abs(bed.x[i]), std::abs(bed.y[i]), std::abs(bed.z[i])});
    max_radius = std::max(max_radius, bed.radius[i]);
  }
  const double r_min = *std::min_element(bed.radius.begin(), bed.radius.end());
  // Half a unit in the last printed digit, relative: 0.5 10^(1 - digits).
  const double half_unit = 0.5 * std::pow(10.0, 1 - digits);
  const double gap_error = 2 * std::sqrt(3.0) * half_unit * max_centre + 2 * half_unit * max_radius;
  const double criterion = tolerance * 2 * r_min;
  if (gap_error <= criterion) return "";
  char text[320];
  std::snprintf(text, sizeof text,
                "printed with %d significant digits: a gap may be off by %.3g m, above the "
                "contact tolerance %.3g x (r_i + r_j) = %.3g m of the smallest pair, so contact "
                "counts are not reliable (write dumps with dump_modify format float %%.17g)",
                digits, gap_error, tolerance, criterion);
  return text;
}

}  // namespace powderbed::bed
