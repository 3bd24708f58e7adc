#pragma once
// Tests on a double written as integer operations on its IEEE 754 binary64 bits, for loops that
// reduce a per-particle test to one flag. GCC 12 vectorises no loop that turns a floating-point
// comparison into an integer ("no vectype" for the comparison's mask), so a loop with
// `flag |= (a > b)` runs one particle at a time; these shifts, masks and ORs of 64-bit integers
// are SSE2 instructions, and the loop runs two particles at a time with the same answer.
#include <bit>
#include <cstdint>

namespace powderbed::dem::detail {

// 1 when v is Inf or NaN (its 11 exponent bits all set), else 0.
inline std::uint64_t non_finite_bit(double v) {
  return (((std::bit_cast<std::uint64_t>(v) >> 52) & 0x7FF) + 1) >> 11;
}

// 1 when a > b, else 0: the sign bit of b - a, which rounding never flips and which is set on
// a zero difference only for (-0) - (+0). For a, b not NaN and b > 0.
inline std::uint64_t above_bit(double a, double b) { return std::bit_cast<std::uint64_t>(b - a) >> 63; }

}  // namespace powderbed::dem::detail
