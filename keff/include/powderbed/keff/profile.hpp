#pragma once
// The binned temperature profile of a keff run along its axis: what a reader compares with the
// straight line of a uniform conductor, and where the walls' contact resistances show as jumps.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "powderbed/bed/bed.hpp"

namespace powderbed::keff {

struct TemperatureProfile {
  // One entry per bin, from the cold wall (domain.lower of the axis) to the hot wall.
  std::vector<double> position;     // bin centre along the axis, m
  std::vector<double> mean;         // mean temperature of the particles centred in the bin, K
  std::vector<double> min, max;     // K; all three NaN where the bin holds no particle
  std::vector<std::uint64_t> particles;
};

// `bins` equal bins between the walls (0: one per mean particle diameter, at least one).
// Particles listed in `excluded` (ascending indices: the rattlers, whose temperature is not a
// steady state) are left out.
TemperatureProfile temperature_profile(const bed::Bed& bed, int axis,
                                       const std::vector<double>& temperature,
                                       const std::vector<std::uint32_t>& excluded,
                                       std::size_t bins);

// Linearity of the profile: R² = 1 − Σ (T_b − T̂_b)² / Σ (T_b − T̄)² of the bin means T_b
// (empty bins left out, each bin one point) against their least-squares line T̂ in position:
// 1 for a straight line, lower where the wall layers take jumps. NaN with fewer than 3 bins
// holding particles (two points always lie on a line).
double profile_r_squared(const TemperatureProfile& profile);

}  // namespace powderbed::keff
