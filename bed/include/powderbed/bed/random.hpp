#pragma once
// One random engine and the few draws every stage needs, written out so that a seed gives the
// same bed bit for bit with any standard library (std:: distributions are implementation-defined).
#include <cstdint>
#include <random>

namespace powderbed::bed {

using Rng = std::mt19937_64;

// Uniform double in [0, 1) from the top 53 bits.
inline double uniform01(Rng& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

inline double uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * uniform01(rng); }

// Uniform integer in [0, n) (n > 0), by Lemire's multiply-shift without rejection: the bias is
// below n / 2^64, far under any statistic we compute.
__extension__ typedef unsigned __int128 Uint128;  // a GCC/Clang extension: __extension__ keeps -Wpedantic quiet
inline std::uint64_t uniform_index(Rng& rng, std::uint64_t n) {
  return static_cast<std::uint64_t>((static_cast<Uint128>(rng()) * n) >> 64);
}

}  // namespace powderbed::bed
