#pragma once
// An option whose value is one of a few words (laser.optics = fresnel | constant). Each library
// keeps one table of its words and the values they name beside the enum (e.g.
// thermal/scene_words.hpp), and parse_word reads a word with it: the words an error offers are
// the words the table accepts, from one list.
#include <fmt/format.h>

#include <cstddef>
#include <string>
#include <string_view>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

template <class E>
struct OptionWord {
  std::string_view text;
  E value;
};

// The value `text` names in `words`; InputError "OPTION: 'TEXT' (accepted: a, b)" otherwise, or
// "OPTION: 'TEXT' is not WHAT (accepted: ...)" when `what` names the kind of thing.
template <class E, std::size_t N>
E parse_word(std::string_view text, std::string_view option, const OptionWord<E> (&words)[N],
             std::string_view what = {}) {
  for (const OptionWord<E>& w : words)
    if (w.text == text) return w.value;
  std::string accepted;
  for (const OptionWord<E>& w : words) accepted += (accepted.empty() ? "" : ", ") + std::string(w.text);
  const std::string is_not = what.empty() ? "" : fmt::format(" is not {}", what);
  throw InputError(fmt::format("{}: '{}'{} (accepted: {})", option, text, is_not, accepted));
}

}  // namespace powderbed::bed
