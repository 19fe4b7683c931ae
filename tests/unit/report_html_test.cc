// The report page's building blocks: base64 against RFC 4648's test vectors, gnuplot string
// quoting that no name can break out of.
#include <gtest/gtest.h>

#include "vstcal/core/error.h"
#include "vstcal/report/gnuplot.h"
#include "vstcal/report/html.h"
#include "vstcal/report/html_page.h"

namespace vstcal {
namespace {

TEST(Base64, Rfc4648TestVectors) {  // RFC 4648 §10
  EXPECT_EQ(html::Base64(""), "");
  EXPECT_EQ(html::Base64("f"), "Zg==");
  EXPECT_EQ(html::Base64("fo"), "Zm8=");
  EXPECT_EQ(html::Base64("foo"), "Zm9v");
  EXPECT_EQ(html::Base64("foob"), "Zm9vYg==");
  EXPECT_EQ(html::Base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(html::Base64("foobar"), "Zm9vYmFy");
  const unsigned char high[] = {0xfb, 0xff, 0xfe};
  EXPECT_EQ(html::Base64(high, 3), "+//+");
}

TEST(GnuplotQuoted, NamesCannotEndTheStringOrTheLine) {
  EXPECT_EQ(GnuplotQuoted("plane-00"), "\"plane-00\"");
  EXPECT_EQ(GnuplotQuoted("a\"; system(\"rm\")"), "\"a\\\"; system(\\\"rm\\\")\"");
  EXPECT_EQ(GnuplotQuoted("back\\slash"), "\"back\\\\slash\"");
  EXPECT_EQ(GnuplotQuoted("two\nlines"), "\"two lines\"");
}

TEST(RunGnuplot, DrawsAnSvgAndReportsItsErrors) {
  const std::string svg = RunGnuplot("set terminal svg size 200,100\nset output\n$d << EOD\n0 0\n1 1\nEOD\nplot $d with lines notitle\n");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  try {
    RunGnuplot("set terminal svg\nset output\nplot nosuchfunction(x)\n");
    FAIL() << "gnuplot's error was not reported";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("gnuplot failed: "), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vstcal
