#pragma once
// The volume of a sphere of radius r, V = 4/3 pi r^3: every part that turns a radius into a
// volume (packing fractions, the DEM's masses rho V, the decks' mean masses) takes it here.
#include <numbers>

namespace powderbed::bed {

// Evaluated left to right, (((4/3 pi) r) r) r, the order every caller used before it moved here,
// so that moving it changed no result.
inline double sphere_volume(double radius) {
  return 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

}  // namespace powderbed::bed
