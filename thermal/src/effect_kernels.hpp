#pragma once
// Kernels composed from the scene's effects (docs/architecture.md "Effects a scene calls for"):
// a kernel is a template over a set of SinterEffect bits, instantiated for every combination of
// the few effects that shape it and put in a table, and a run picks its entry once, by the
// scene's effects. Each kernel names the effects that shape it in an array of the scene's own
// bits (scene.hpp), so the scene's table stays the one list of effects.
#include <array>
#include <cstddef>

#include "powderbed/thermal/scene.hpp"

namespace powderbed::thermal {

// The effects of `shaping` whose bits are set in `index` (bit b: shaping[b]): the template
// argument of a kernel table's entry `index`.
template <std::size_t N>
constexpr unsigned effects_of_index(const std::array<SinterEffect, N>& shaping, std::size_t index) {
  unsigned effects = 0;
  for (std::size_t b = 0; b < N; ++b)
    if ((index >> b) & 1u) effects |= shaping[b];
  return effects;
}

// The table entry of the scene's `effects`: which of `shaping` are on (the rest ignored).
template <std::size_t N>
constexpr std::size_t index_of_effects(const std::array<SinterEffect, N>& shaping,
                                       unsigned effects) {
  std::size_t index = 0;
  for (std::size_t b = 0; b < N; ++b)
    if ((effects & shaping[b]) != 0) index |= std::size_t{1} << b;
  return index;
}

}  // namespace powderbed::thermal
