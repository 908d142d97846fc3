#include "drvslam/core/enum_names.h"

#include <gtest/gtest.h>

namespace drvslam {
namespace {

enum class Colour { kRed, kGreen, kBlue };

const char* ColourName(Colour colour) {
  static constexpr EnumName<Colour> kNames[] = {{Colour::kRed, "red"}, {Colour::kGreen, "green"}};
  return NameOf(colour, kNames, "unknown");
}

// Usable in constant expressions too.
constexpr EnumName<Colour> kInitials[] = {{Colour::kGreen, "g"}};
static_assert(NameOf(Colour::kGreen, kInitials, "?")[0] == 'g');
static_assert(NameOf(Colour::kRed, kInitials, "?")[0] == '?');

TEST(EnumNamesTest, ListedValuesGetTheirNameAndOthersTheFallback) {
  EXPECT_STREQ(ColourName(Colour::kRed), "red");
  EXPECT_STREQ(ColourName(Colour::kGreen), "green");
  // Not in the table, and a value cast from a bad integer.
  EXPECT_STREQ(ColourName(Colour::kBlue), "unknown");
  EXPECT_STREQ(ColourName(static_cast<Colour>(7)), "unknown");
}

}  // namespace
}  // namespace drvslam
