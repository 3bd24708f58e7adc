// bed::parse_word: a word of an option's table gives its value; any other exits with one line
// naming the option, the word and every word the table accepts, in the table's order.
#include <gtest/gtest.h>

#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/option_words.hpp"

namespace {

enum class Colour { red, green, blue };
constexpr powderbed::bed::OptionWord<Colour> kColours[] = {
    {"red", Colour::red}, {"green", Colour::green}, {"blue", Colour::blue}};

std::string refusal(const std::string& text, const std::string& what = "") {
  try {
    powderbed::bed::parse_word(text, "paint.colour", kColours, what);
  } catch (const powderbed::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST(OptionWords, EachWordGivesItsValue) {
  EXPECT_EQ(powderbed::bed::parse_word("red", "paint.colour", kColours), Colour::red);
  EXPECT_EQ(powderbed::bed::parse_word("blue", "paint.colour", kColours), Colour::blue);
}

TEST(OptionWords, AnyOtherWordIsRefusedWithTheTablesWords) {
  EXPECT_EQ(refusal("Red"), "paint.colour: 'Red' (accepted: red, green, blue)");
  EXPECT_EQ(refusal(""), "paint.colour: '' (accepted: red, green, blue)");
  EXPECT_EQ(refusal("mauve", "a colour"), "paint.colour: 'mauve' is not a colour (accepted: red, green, blue)");
}
