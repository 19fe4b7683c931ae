// core/option_name.h: a library message names options neutrally, and each front end renders them.
#include <gtest/gtest.h>

#include <string>

#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

TEST(OptionName, EachFrontEndRendersTheNamesItsUserTyped) {
  const std::string message = VSTCAL_OPT("tilt_deg") ": must lie within ±80°; or drop " + Opt("max_tilt_deg");
  EXPECT_EQ(RenderOptionNames(message, OptionAsFlag), "--tilt-deg: must lie within ±80°; or drop --max-tilt-deg");
  EXPECT_EQ(RenderOptionNames(message, OptionAsKeyword), "tilt_deg: must lie within ±80°; or drop max_tilt_deg");
  EXPECT_EQ(std::string(VSTCAL_OPT("z")), Opt("z"));
}

TEST(OptionName, TextWithoutCompleteMarksIsLeftAlone) {
  for (const std::string& text : {std::string("plain -- text, views[2], \"quoted\""), std::string(""),
                                 std::string("unterminated \u2039name"), std::string("stray \u203a close")}) {
    EXPECT_EQ(RenderOptionNames(text, OptionAsFlag), text);
  }
  EXPECT_EQ(RenderOptionNames("\u2039a\u203a\u2039b_c\u203a", OptionAsFlag), "--a--b-c");
  EXPECT_EQ(RenderOptionNames("x \u2039a\u203a y \u2039b", OptionAsFlag), "x --a y \u2039b");
}

}  // namespace
}  // namespace vstcal
