// The --times file (formats/capture/image_times.h): either order of name and time, spaces, tabs or
// commas, comments, units; each refusal names the line.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "vstcal/core/error.h"
#include "vstcal/formats/capture/image_times.h"

namespace vstcal {
namespace {

const std::vector<std::string> kImageNames = {"a.png", "b.png", "1403636579763555584.png"};

std::string ErrorOf(const std::string& text, TimeUnit unit = TimeUnit::kSecond) {
  try {
    ImageTimesFromText(text, "t.txt", kImageNames, unit);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ImageTimes, EitherOrderAnySeparatorAndUnits) {
  const auto t = ImageTimesFromText("# name time\n a.png\t1.5\r\n0.25, b.png\n\n", "t.txt", kImageNames, TimeUnit::kSecond);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.at("a.png"), 1.5);
  EXPECT_EQ(t.at("b.png"), 0.25);
  EXPECT_DOUBLE_EQ(ImageTimesFromText("a.png 250", "t.txt", kImageNames, TimeUnit::kMillisecond).at("a.png"), 0.25);
  EXPECT_DOUBLE_EQ(ImageTimesFromText("a.png 250", "t.txt", kImageNames, TimeUnit::kMicrosecond).at("a.png"), 250e-6);
  // EuRoC: the name is the time in nanoseconds; the field that is an image's name is the name.
  const auto euroc = ImageTimesFromText("1403636579763555584,1403636579763555584.png\n", "t.txt", kImageNames, TimeUnit::kNanosecond);
  EXPECT_NEAR(euroc.at("1403636579763555584.png"), 1403636579.763555584, 1e-6);
}

TEST(ImageTimes, RefusalsNameTheLine) {
  EXPECT_EQ(ErrorOf("a.png 1\nb.png 2 3\n"),
            "t.txt: line 2: 3 fields where a line has 2 (the image's file name and its time); write one image a line, or comment the line out with #");
  EXPECT_NE(ErrorOf("c.png 1\n").find("line 1: neither \"c.png\" nor \"1\" is the file name of an image given"), std::string::npos);
  EXPECT_NE(ErrorOf("a.png nan\n").find("line 1: \"nan\" is not a finite number"), std::string::npos);
  EXPECT_NE(ErrorOf("a.png 1e999\n").find("line 1: \"1e999\" is not a finite number"), std::string::npos);
  EXPECT_NE(ErrorOf("a.png 1\na.png 2\n").find("line 2: \"a.png\" has a time already"), std::string::npos);
}

}  // namespace
}  // namespace vstcal
