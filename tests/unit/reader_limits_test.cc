// The limits of the OpenCV YAML and .cameramodel readers (docs/reliability.md#limits): nesting is
// bounded before cv::FileStorage sees the text, sizes and value counts are bounded, and an image
// side beyond 1,000,000 px says so in every format.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "support/error_of.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/formats/camera/mrcal_cameramodel.h"
#include "vstcal/formats/camera/opencv_yaml.h"

namespace vstcal {
namespace {

std::string YamlError(const std::string& text) {
  return testing::ErrorOf([&] { OpenCvYamlFromText(text, "t.yaml", LengthUnit::kMillimetre); });
}

std::string MrcalError(const std::string& text) {
  return testing::ErrorOf([&] { MrcalCameramodelFromText(text, "t.cameramodel", std::nullopt); });
}

// The bound 2·(indentation + indicators) + brackets + 1 against 64: after "a: " (one indicator),
// 61 flow brackets pass the check (OpenCV parses them, and the file is refused for what it
// lacks), 62 do not.
TEST(ReaderLimits, YamlNestingIsBoundedBeforeOpenCvParses) {
  const std::string head = "%YAML:1.0\n---\na: ";
  EXPECT_NE(YamlError(head + std::string(61, '[') + std::string(61, ']') + "\n").find("camera_matrix: missing field"),
            std::string::npos);
  EXPECT_NE(YamlError(head + std::string(62, '[') + std::string(62, ']') + "\n").find("nested too deeply"),
            std::string::npos);
  // Block sequences: each "- " counts twice (a sequence may sit at its key's indentation); the
  // 32nd, at column 63, takes the bound to 65.
  std::string block = "%YAML:1.0\n---\na:\n";
  for (int i = 0; i < 32; ++i) block += "- ";
  EXPECT_NE(YamlError(block + "x\n").find("line 4, column 63: nested too deeply"), std::string::npos)
      << YamlError(block + "x\n");
}

// cv::FileStorage 4.6 never returns from the first kind (libFuzzer found it): its first collection
// ends before the text does, and it steps over 3 bytes as if they were "...". Refused first, with
// the other text libFuzzer found it mishandling.
TEST(ReaderLimits, YamlThatHangsOpenCvIsRefusedBeforeItParses) {
  EXPECT_EQ(YamlError("%YAML:1.0\n -a\n:\n-"),
            "t.yaml: line 2, column 2: the top level is indented; start its fields in the first column, as "
            "cv::FileStorage writes them");
  const std::pair<const char*, const char*> cases[] = {
      {"%YAML:1.0\n---\n# comment\n   camera_matrix: 1\nx: 2\n", "line 4, column 4: the top level is indented"},
      {"%YAML:1.0\n---\na: 1\n...\nb: 2\n", "line 5, column 1: text after the document's end"},
      {"%YAML:1.0\n---\na: 1\n---\n -a\n:\n-\n", "line 4, column 1: a second YAML document (\"---\")"},
      {"%YAML:1.0\n--- a: 1\nb: 2\n", "line 2, column 5: text after \"---\" on its line"},
      {"%YAML:1.0\n---\na: 1\n...\n# the end\n...\n", "line 6, column 1: text after the document's end"},
      // An indented empty key made cv::FileStorage throw std::length_error.
      {"%YAML:1.0\n---\nm:\n   r: 3\n   :ols: 3\n", "line 5, column 4: an empty key"},
      // A number beyond the doubles, read as ∞, went through the writer's number formatting,
      // which refuses ∞.
      {"%YAML:1.0\ncamera_matrix: 1e999\n",
       "camera_matrix: expected an !!opencv-matrix (rows, cols, dt, data), got a number beyond the doubles (inf)"},
      // What cv::FileStorage writes passes (and is refused for what it lacks): a directive, "---",
      // comments, fields from the first column, and a closing "..." (YAML's document end).
      {"%YAML:1.0\n---\n# c\n\na: 1\n", "camera_matrix: missing field"},
      {"%YAML:1.0\n---\na: 1\n...\n# the end\n", "camera_matrix: missing field"},
  };
  for (const auto& [text, message] : cases) {
    EXPECT_NE(YamlError(text).find(message), std::string::npos) << text << "\n" << YamlError(text);
  }
}

TEST(ReaderLimits, YamlSizeIsBounded) {
  std::string text = "%YAML:1.0\n---\n# " + std::string(limits::kMaxOpenCvYamlBytes, 'x') + "\n";
  EXPECT_NE(YamlError(text).find("larger than the 16 MiB vstcal reads as OpenCV YAML"), std::string::npos);
}

TEST(ReaderLimits, CameramodelValuesAreBounded) {
  std::string many = "{'a': [";
  for (size_t i = 0; i <= limits::kMaxLiteralValues; ++i) many += "0,";
  EXPECT_NE(MrcalError(many + "]}").find("more than 1048576 values"), std::string::npos);
}

TEST(ReaderLimits, ImageSideBeyondTheLimitSaysSoInEveryFormat) {
  const std::string yaml = "%YAML:1.0\n---\nimage_width: 10000000000\nimage_height: 480\n"
                           "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
                           "   data: [ 600., 0., 319.5, 0., 600., 239.5, 0., 0., 1. ]\n";
  // cv::FileStorage would read 10000000000 as 1410065408, and 4294967936 as 640: refused first.
  EXPECT_NE(YamlError(yaml).find("line 3, column 14: the integer 10000000000 is beyond the 32-bit integers"),
            std::string::npos)
      << YamlError(yaml);
  std::string wraps_to_640 = yaml;
  wraps_to_640.replace(wraps_to_640.find("10000000000"), 11, "4294967936");
  EXPECT_NE(YamlError(wraps_to_640).find("the integer 4294967936 is beyond"), std::string::npos) << YamlError(wraps_to_640);
  std::string beyond_limit = yaml;
  beyond_limit.replace(beyond_limit.find("10000000000"), 11, "2000000");
  EXPECT_NE(YamlError(beyond_limit).find("image_width: 2000000 px is more than the 1000000 px per side"), std::string::npos)
      << YamlError(beyond_limit);
  const std::string mrcal = "{'lensmodel': 'LENSMODEL_PINHOLE', 'intrinsics': [600, 600, 319.5, 239.5], "
                            "'extrinsics': [0, 0, 0, 0, 0, 0], 'imagersize': [640, 10000000000]}";
  EXPECT_NE(MrcalError(mrcal).find("imagersize[1]: 10000000000 px is more than the 1000000 px per side"),
            std::string::npos)
      << MrcalError(mrcal);
}

}  // namespace
}  // namespace vstcal
