// CLI tests of calib-dlt: every bad input a user can give gets the documented exit code, one
// actionable line on stderr naming the file and the field, and no output file; good input gives
// a valid, reproducible vstcal/camera@1 file.
#include <algorithm>
#include <cctype>
#include <functional>
#include <ostream>

#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

const std::vector<std::string> kOutputs = {"-o", "out/camera.json", "--residuals", "out/residuals.json"};

std::vector<std::string> DltArgs(const std::string& input, std::vector<std::string> extra = kOutputs) {
  extra.insert(extra.begin(), input);
  return extra;
}

using CliCalibDlt = CliTest;

// ---------------------------------------------------------------------------------------------
// The file itself: missing, a directory, empty, not JSON, non-finite numbers.

TEST_F(CliCalibDlt, MissingInputFile) {
  const auto r = Run("calib-dlt", DltArgs("in/missing.json"));
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "in/missing.json: ", {"no such file", "check the path"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, InputIsADirectory) {
  const auto r = Run("calib-dlt", DltArgs("in"));
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "in: ", {"is a directory", "give the file's path"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, EmptyFile) {
  WriteText("in/empty.json", "");
  const auto r = Run("calib-dlt", DltArgs("in/empty.json"));
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "in/empty.json: ", {"the file is empty", "expected a JSON object"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, WhitespaceOnlyFile) {
  WriteText("in/blank.json", " \n\t\n");
  const auto r = Run("calib-dlt", DltArgs("in/blank.json"));
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "in/blank.json: ", {"the file is empty"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, SyntaxErrorReportsLineAndColumn) {
  // A missing comma between 640 and 480: the unexpected token starts at line 3, column 21.
  WriteText("in/bad.json", "{\n \"format\": \"vstcal/correspondences@1\",\n \"image_size\": [640 480]\n}\n");
  const auto r = Run("calib-dlt", DltArgs("in/bad.json"));
  EXPECT_TRUE(
      FailsWith(r, "calib-dlt", kBadInput, "in/bad.json: line 3, column 21: ", {"not valid JSON", "fix the syntax"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, TruncatedFile) {
  const std::string text = Synth().dump(2);
  WriteText("in/bad.json", text.substr(0, text.size() / 2));
  const auto r = Run("calib-dlt", DltArgs("in/bad.json"));
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "in/bad.json: line ", {"not valid JSON", "fix the syntax"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, TrailingGarbage) {
  WriteText("in/bad.json", Synth().dump(2) + "\n}\n");
  const auto r = Run("calib-dlt", DltArgs("in/bad.json"));
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "in/bad.json: line ", {"not valid JSON"}));
  EXPECT_TRUE(OutDirEmpty());
}

// A literal that is not a finite JSON number, written in place of views[0].points[3][3] (u).
struct NonFiniteLiteral {
  std::string name;
  std::string token;
  std::string phrase;  // what the message says about it
};

void PrintTo(const NonFiniteLiteral& c, std::ostream* os) { *os << c.name; }

class CliCalibDltNonFinite : public CliTest, public ::testing::WithParamInterface<NonFiniteLiteral> {};

TEST_P(CliCalibDltNonFinite, NamesLineColumnAndToken) {
  const NonFiniteLiteral& c = GetParam();
  Json doc = Synth();
  doc["views"][0]["points"][3][3] = "@@HERE@@";
  std::string text = doc.dump(2);
  const size_t at = text.find("\"@@HERE@@\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 10, c.token);
  WriteText("in/bad.json", text);

  const auto r = Run("calib-dlt", DltArgs("in/bad.json"));
  const std::string shown = c.token.size() <= 24 ? c.token : c.token.substr(0, 20) + "...";
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "in/bad.json: " + LineColumn(text, at) + ": ",
                        {"'" + shown + "' " + c.phrase, "every value must be a finite number"}));
  EXPECT_TRUE(OutDirEmpty());
}

INSTANTIATE_TEST_SUITE_P(Literals, CliCalibDltNonFinite,
                         ::testing::Values(NonFiniteLiteral{"NaN", "NaN", "is not a JSON number"},
                                           NonFiniteLiteral{"Infinity", "Infinity", "is not a JSON number"},
                                           NonFiniteLiteral{"MinusInfinity", "-Infinity", "is not a JSON number"},
                                           NonFiniteLiteral{"Overflow1e999", "1e999", "is too large for a double"},
                                           NonFiniteLiteral{"OverflowMinus1e999", "-1e999",
                                                            "is too large for a double"},
                                           NonFiniteLiteral{"Overflow1E400", "1E+400", "is too large for a double"},
                                           NonFiniteLiteral{"OverflowLongInteger", "1" + std::string(400, '0'),
                                                            "is too large for a double"}),
                         [](const auto& param_info) { return param_info.param.name; });

// ---------------------------------------------------------------------------------------------
// Bad content: each case edits a valid synthetic volume (60 points, camera at (0, 0, −1500),
// views plane-00/01/02 at Z = 0/200/400) and names the field the message must point to.

struct BadVolume {
  std::string name;
  int exit_code;
  std::string field;  // "" when the message is about the data as a whole
  std::vector<std::string> phrases;
  std::function<void(Json& doc, const Pinhole& camera)> edit;
  std::vector<std::string> synth_args = {};  // empty: DefaultSynthArgs()
};

void PrintTo(const BadVolume& c, std::ostream* os) { *os << c.name; }

Json& Point(Json& doc, size_t view, size_t index) { return doc["views"][view]["points"][index]; }

// Keeps only the listed views.
void KeepViews(Json& doc, std::initializer_list<size_t> keep) {
  Json views = Json::array();
  for (size_t v : keep) views.push_back(doc["views"][v]);
  doc["views"] = std::move(views);
}

// `n` points on a line through the volume, with their exact pixels.
Json LinePoints(const Pinhole& cam, int n) {
  Json points = Json::array();
  for (int k = 0; k < n; ++k) points.push_back(cam.Observe(Eigen::Vector3d(-150 + 40 * k, -60 + 15 * k, 50 * k)));
  return points;
}

std::vector<BadVolume> BadVolumes() {
  std::vector<BadVolume> cases = {
      // Top level and "format".
      {"RootIsArray",
       kBadInput,
       "(top level)",
       {"expected an object, got an array", "write it as a JSON object"},
       [](Json& d, const Pinhole&) { d = Json::array({d}); }},
      {"FormatOfAnotherSchema",
       kBadInput,
       "format",
       {"this is a \"vstcal/camera@1\" file", "expected \"vstcal/correspondences@1\"", "pass the right file"},
       [](Json& d, const Pinhole&) { d["format"] = "vstcal/camera@1"; }},
      {"FormatOfAnotherMajorVersion",
       kBadInput,
       "format",
       {"unsupported version \"vstcal/correspondences@2\"", "this vstcal reads \"vstcal/correspondences@1\""},
       [](Json& d, const Pinhole&) { d["format"] = "vstcal/correspondences@2"; }},
      {"FormatForeign",
       kBadInput,
       "format",
       {"unknown format \"opencv-storage\"", "docs/formats.md"},
       [](Json& d, const Pinhole&) { d["format"] = "opencv-storage"; }},
      {"FormatNotAString",
       kBadInput,
       "format",
       {"expected a string, got the number 1", "double quotes"},
       [](Json& d, const Pinhole&) { d["format"] = 1; }},
      // A newline inside a quoted value must not break the one-line message.
      {"FormatWithNewline",
       kBadInput,
       "format",
       {"unknown format \"vstcal\\ncorrespondences\""},
       [](Json& d, const Pinhole&) { d["format"] = "vstcal\ncorrespondences"; }},

      // Missing required fields.
      {"MissingFormat",
       kBadInput,
       "format",
       {"missing field", "add \"format\""},
       [](Json& d, const Pinhole&) { d.erase("format"); }},
      {"MissingImageSize",
       kBadInput,
       "image_size",
       {"missing field", "add \"image_size\""},
       [](Json& d, const Pinhole&) { d.erase("image_size"); }},
      {"MissingLengthUnit",
       kBadInput,
       "length_unit",
       {"missing field", "add \"length_unit\""},
       [](Json& d, const Pinhole&) { d.erase("length_unit"); }},
      {"MissingRig",
       kBadInput,
       "rig",
       {"missing field", "add \"rig\""},
       [](Json& d, const Pinhole&) { d.erase("rig"); }},
      {"MissingViews",
       kBadInput,
       "views",
       {"missing field", "add \"views\""},
       [](Json& d, const Pinhole&) { d.erase("views"); }},
      {"MissingViewPoints",
       kBadInput,
       "views[1].points",
       {"missing field", "add \"points\""},
       [](Json& d, const Pinhole&) { d["views"][1].erase("points"); }},
      {"MissingViewName",
       kBadInput,
       "views[2].name",
       {"missing field", "add \"name\""},
       [](Json& d, const Pinhole&) { d["views"][2].erase("name"); }},
      {"TestPointPixelOutsideImage",
       kBadInput,
       "test_points[0].pixel",
       {"lies outside the 640×480 image", "omit \"pixel\""},
       [](Json& d, const Pinhole&) {
         d["test_points"] = Json::array({{{"name", "Left"}, {"world", {0, 0, 100}}, {"pixel", {700, 10}}}});
       }},
      {"MissingTestPointWorld",
       kBadInput,
       "test_points[0].world",
       {"missing field", "add \"world\""},
       [](Json& d, const Pinhole&) {
         d["test_points"] = Json::array({{{"name", "Left"}, {"pixel", {1, 2}}}});
       }},

      // image_size.
      {"ImageSizeThreeEntries",
       kBadInput,
       "image_size",
       {"expected 2 items, got 3", "give exactly 2"},
       [](Json& d, const Pinhole&) {
         d["image_size"] = {640, 480, 3};
       }},
      {"ImageSizeNegative",
       kBadInput,
       "image_size[0]",
       {"must be a positive integer, got -640", "give the image width in pixels, a whole number from 1 to 1000000"},
       [](Json& d, const Pinhole&) {
         d["image_size"] = {-640, 480};
       }},
      {"ImageSizeZero",
       kBadInput,
       "image_size[1]",
       {"must be a positive integer, got 0"},
       [](Json& d, const Pinhole&) {
         d["image_size"] = {640, 0};
       }},
      {"ImageSizeNotInteger",
       kBadInput,
       "image_size[0]",
       {"expected an integer, got 640.5", "give the image width in pixels, a whole number from 1 to 1000000"},
       [](Json& d, const Pinhole&) {
         d["image_size"] = {640.5, 480};
       }},
      {"ImageSizeAsString",
       kBadInput,
       "image_size",
       {"expected an array, got the string \"640x480\""},
       [](Json& d, const Pinhole&) { d["image_size"] = "640x480"; }},
      {"ImageSizeNull",
       kBadInput,
       "image_size[1]",
       {"expected a number, got null"},
       [](Json& d, const Pinhole&) {
         d["image_size"] = {640, nullptr};
       }},

      // length_unit and rig.
      {"UnknownLengthUnit",
       kBadInput,
       "length_unit",
       {"unknown value \"inch\"", "use one of \"mm\", \"cm\", \"m\""},
       [](Json& d, const Pinhole&) { d["length_unit"] = "inch"; }},
      {"LengthUnitNotAString",
       kBadInput,
       "length_unit",
       {"expected a string"},
       [](Json& d, const Pinhole&) { d["length_unit"] = 1000; }},
      {"UnknownRig",
       kBadInput,
       "rig",
       {"unknown value \"stereo\"", "use one of \"volume\", \"planar-views\""},
       [](Json& d, const Pinhole&) { d["rig"] = "stereo"; }},
      {"PlanarViewsRigForDlt",
       kBadInput,
       "rig",
       {"DLT needs one world frame", "calib-tsai"},
       [](Json& d, const Pinhole&) {
         // A valid planar-views file (every point at Z = 0), but DLT cannot solve it.
         KeepViews(d, {0, 0});
         d["views"][1]["name"] = "plane-00-again";
         d["rig"] = "planar-views";
       }},
      {"PlanarViewsRigWithVolumePoints",
       kBadInput,
       "views[1].points[0][2]",
       {"planar-views points lie on their board (Z = 0), got Z = 200", "use \"rig\": \"volume\""},
       [](Json& d, const Pinhole&) { d["rig"] = "planar-views"; }},

      // views.
      {"ViewsNotAnArray",
       kBadInput,
       "views",
       {"expected an array, got an object", "JSON array"},
       [](Json& d, const Pinhole&) { d["views"] = Json::object(); }},
      {"NoViews",
       kBadInput,
       "views",
       {"no views", "add at least one view"},
       [](Json& d, const Pinhole&) { d["views"] = Json::array(); }},
      {"ViewNotAnObject",
       kBadInput,
       "views[0]",
       {"expected an object, got the number 5"},
       [](Json& d, const Pinhole&) { d["views"][0] = 5; }},
      {"ViewWithoutPoints",
       kBadInput,
       "views[1].points",
       {"the view has no points", "remove the view or add its points"},
       [](Json& d, const Pinhole&) { d["views"][1]["points"] = Json::array(); }},
      {"DuplicateViewNames",
       kBadInput,
       "views[2].name",
       {"duplicate view name \"plane-00\"", "give every view a unique name"},
       [](Json& d, const Pinhole&) { d["views"][2]["name"] = "plane-00"; }},
      {"EmptyViewName",
       kBadInput,
       "views[1].name",
       {"empty view name", "give every view a unique name"},
       [](Json& d, const Pinhole&) { d["views"][1]["name"] = ""; }},
      {"ViewNameNotAString",
       kBadInput,
       "views[1].name",
       {"expected a string, got the number 3"},
       [](Json& d, const Pinhole&) { d["views"][1]["name"] = 3; }},
      {"PlaneOffsetNotANumber",
       kBadInput,
       "views[1].plane_offset",
       {"expected a number, got the string \"far\""},
       [](Json& d, const Pinhole&) { d["views"][1]["plane_offset"] = "far"; }},
      {"PointsNotAnArray",
       kBadInput,
       "views[1].points",
       {"expected an array, got an object"},
       [](Json& d, const Pinhole&) { d["views"][1]["points"] = Json::object(); }},

      // Points: shapes, types, values.
      {"PointWithFourNumbers",
       kBadInput,
       "views[0].points[3]",
       {"expected 5 numbers [X, Y, Z, u, v] or 6 with a weight, got 4",
        "write each point as [X, Y, Z, u, v], or [X, Y, Z, u, v, weight]"},
       [](Json& d, const Pinhole&) { Point(d, 0, 3).erase(4); }},
      {"PointWithSevenNumbers",
       kBadInput,
       "views[0].points[3]",
       {"expected 5 numbers [X, Y, Z, u, v] or 6 with a weight, got 7", "or [X, Y, Z, u, v, weight]"},
       [](Json& d, const Pinhole&) {
         Point(d, 0, 3).push_back(1.0);
         Point(d, 0, 3).push_back(1.0);
       }},
      {"ZeroWeight",
       kBadInput,
       "views[0].points[3][5]",
       {"the weight must be positive, got 0", "give a weight > 0 (the point's noise is sigma/sqrt(weight)), or remove the point"},
       [](Json& d, const Pinhole&) { Point(d, 0, 3).push_back(0); }},
      {"NegativeWeight",
       kBadInput,
       "views[0].points[3][5]",
       {"the weight must be positive, got -2.5"},
       [](Json& d, const Pinhole&) { Point(d, 0, 3).push_back(-2.5); }},
      {"WeightNotANumber",
       kBadInput,
       "views[0].points[3][5]",
       {"expected a number, got the string \"1\""},
       [](Json& d, const Pinhole&) { Point(d, 0, 3).push_back("1"); }},
      {"PointNotAnArray",
       kBadInput,
       "views[0].points[3]",
       {"expected [X, Y, Z, u, v]", "write each point as"},
       [](Json& d, const Pinhole&) { Point(d, 0, 3) = 1.0; }},
      {"NullCoordinate",
       kBadInput,
       "views[0].points[3][1]",
       {"expected a number, got null", "write a finite number"},
       [](Json& d, const Pinhole&) { Point(d, 0, 3)[1] = nullptr; }},
      {"StringCoordinate",
       kBadInput,
       "views[2].points[7][2]",
       {"expected a number, got the string \"400\""},
       [](Json& d, const Pinhole&) { Point(d, 2, 7)[2] = "400"; }},
      {"BooleanPixel",
       kBadInput,
       "views[1].points[0][4]",
       {"expected a number, got true"},
       [](Json& d, const Pinhole&) { Point(d, 1, 0)[4] = true; }},
      {"PixelRightOfImage",
       kBadInput,
       "views[0].points[3]",
       {"pixel (640, ", "lies outside the 640×480 image", "check image_size"},
       [](Json& d, const Pinhole&) { Point(d, 0, 3)[3] = 640; }},
      {"PixelAboveImage",
       kBadInput,
       "views[1].points[2]",
       {"pixel (", ", -0.6) lies outside the 640×480 image"},
       [](Json& d, const Pinhole&) { Point(d, 1, 2)[4] = -0.6; }},
      {"PixelsForASmallerImage",
       kBadInput,
       "views[0].points[3]",
       {"lies outside the 320×240 image"},
       [](Json& d, const Pinhole&) {
         d["image_size"] = {320, 240};
       }},

      // Optional fields, when present, are checked too.
      {"CameraNameNotAString",
       kBadInput,
       "camera",
       {"expected a string"},
       [](Json& d, const Pinhole&) { d["camera"] = 3; }},
      {"TestPointWorldWithTwoNumbers",
       kBadInput,
       "test_points[0].world",
       {"expected 3 items, got 2", "give exactly 3"},
       [](Json& d, const Pinhole&) {
         d["test_points"] = Json::array({{{"name", "Left"}, {"world", {1, 2}}}});
       }},
      {"DuplicateTestPointNames",
       kBadInput,
       "test_points[1].name",
       {"duplicate test point name \"Left\""},
       [](Json& d, const Pinhole&) {
         d["test_points"] =
             Json::array({{{"name", "Left"}, {"world", {1, 2, 3}}}, {{"name", "Left"}, {"world", {1, 2, 3}}}});
       }},

      // Too little or degenerate geometry.
      {"FewerThanSixPoints",
       kBadInput,
       "",
       {"DLT needs at least 6 points", "got 5", "add correspondences"},
       [](Json& d, const Pinhole&) {
         KeepViews(d, {0});
         Json five = Json::array();
         for (size_t k = 0; k < 5; ++k) five.push_back(Point(d, 0, k));
         d["views"][0]["points"] = five;
       }},
      {"Coplanar",
       kDegenerate,
       "",
       {"the points are coplanar", "calib-tsai", "planar-views"},
       [](Json& d, const Pinhole&) { KeepViews(d, {0}); }},
      {"Collinear",
       kDegenerate,
       "",
       {"the points are collinear", "spread the points over a volume"},
       [](Json& d, const Pinhole& cam) {
         d["views"] = Json::array({{{"name", "line"}, {"points", LinePoints(cam, 10)}}});
       }},
      {"AllPointsCoincide",
       kDegenerate,
       "",
       {"the same 3-D point", "spread over a volume"},
       [](Json& d, const Pinhole&) {
         const Json p = Point(d, 0, 0);
         d["views"] = Json::array({{{"name", "same"}, {"points", Json::array({p, p, p, p, p, p, p, p})}}});
       }},
      {"IllConditioned",
       kDegenerate,
       "",
       {"ill-conditioned", "critical configuration", "add points at other depths"},
       [](Json& d, const Pinhole& cam) {
         // A plane plus a line through the camera centre: a critical configuration for DLT
         // (the system has a two-dimensional null space), though the cloud is a volume.
         const Eigen::Vector3d c = cam.Centre(), towards = Eigen::Vector3d(100, 80, 400) - c;
         Json line = Json::array();
         for (int k = 0; k < 8; ++k) line.push_back(cam.Observe(c + (0.6 + 0.05 * k) * towards));
         KeepViews(d, {0});
         d["views"].push_back({{"name", "ray"}, {"points", line}});
       }},
      {"PointBehindTheCamera",
       kBadInput,
       "",
       {"1 of 60 points lie behind the camera", "views[1].points[7]", "\"plane-01\"", "check their coordinates"},
       [](Json& d, const Pinhole& cam) {
         // Mirrored through the camera centre: the same pixel, but behind the camera.
         Json& p = Point(d, 1, 7);
         const Eigen::Vector3d x(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
         const Eigen::Vector3d behind = 2 * cam.Centre() - x;
         p[0] = behind.x();
         p[1] = behind.y();
         p[2] = behind.z();
       }},
      {"MirroredWorld",
       kBadInput,
       "",
       {"mirrored", "left-handed", "flip one world axis"},
       [](Json& d, const Pinhole&) {
         for (Json& view : d["views"]) {
           for (Json& p : view["points"]) p[0] = -p[0].get<double>();
         }
       }},
      {"NearlyCoplanar",
       kDegenerate,
       "",
       {"the points are nearly coplanar", "calib-tsai", "planar-views"},
       [](Json&, const Pinhole&) {},
       // Two planes 1 mm apart across a 1 m board.
       Override(Override(Override(Override(Override(DefaultSynthArgs(), "--grid", "11x11"), "--far", "1"), "--interval",
                                  "1"),
                         "--camera-distance", "2500"),
                "--spacing", "100")},
  };
  return cases;
}

class CliCalibDltBadVolume : public CliTest, public ::testing::WithParamInterface<BadVolume> {};

TEST_P(CliCalibDltBadVolume, FailsWithOneActionableLineAndNoOutput) {
  const BadVolume& c = GetParam();
  Json doc = Synth("in/volume.json", c.synth_args);
  c.edit(doc, Pinhole::FromTruth(ReadJson("in/volume.truth.json")));
  WriteJson("in/bad.json", doc);

  const auto r = Run("calib-dlt", DltArgs("in/bad.json"));
  EXPECT_TRUE(
      FailsWith(r, "calib-dlt", c.exit_code, "in/bad.json: " + (c.field.empty() ? "" : c.field + ": "), c.phrases));
  EXPECT_TRUE(OutDirEmpty());
}

INSTANTIATE_TEST_SUITE_P(Cases, CliCalibDltBadVolume, ::testing::ValuesIn(BadVolumes()),
                         [](const auto& param_info) { return param_info.param.name; });

// ---------------------------------------------------------------------------------------------
// Outputs: all or nothing.

TEST_F(CliCalibDlt, OutputDirectoryDoesNotExist) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/missing/camera.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput,
                        "out/missing/camera.json: ", {"directory out/missing does not exist", "create it first"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, ResidualsDirectoryMissingWritesNeitherFile) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json", "--residuals", "out/missing/res.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput,
                        "out/missing/res.json: ", {"directory out/missing does not exist", "create it first"}));
  EXPECT_TRUE(OutDirEmpty());  // in particular no out/camera.json
}

TEST_F(CliCalibDlt, OutputIsADirectory) {
  Synth();
  fs::create_directory(Path("out/camera.json"));
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "out/camera.json: ", {"it is a directory", "give a file name"}));
  EXPECT_EQ(List("out"), std::vector<std::string>{"camera.json"});
  EXPECT_TRUE(fs::is_empty(Path("out/camera.json")));
}

TEST_F(CliCalibDlt, ResidualsIsADirectoryWritesNeitherFile) {
  Synth();
  fs::create_directory(Path("out/res"));
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json", "--residuals", "out/res"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "out/res: ", {"it is a directory", "give a file name"}));
  EXPECT_EQ(List("out"), std::vector<std::string>{"res"});
  EXPECT_TRUE(fs::is_empty(Path("out/res")));
}

TEST_F(CliCalibDlt, SameFileForCameraAndResiduals) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json", "--residuals", "out/./camera.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "out/./camera.json: ",
                        {"the same file is given for two outputs", "give each output its own file name"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, FailureLeavesAnExistingOutputUntouched) {
  Json doc = Synth();
  KeepViews(doc, {0});  // coplanar
  WriteJson("in/flat.json", doc);
  WriteText("out/camera.json", "previous result\n");
  const auto r = Run("calib-dlt", DltArgs("in/flat.json"));
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kDegenerate, "in/flat.json: ", {"coplanar"}));
  EXPECT_EQ(List("out"), std::vector<std::string>{"camera.json"});
  EXPECT_EQ(ReadText("out/camera.json"), "previous result\n");
}

// ---------------------------------------------------------------------------------------------
// Usage errors.

TEST_F(CliCalibDlt, UnknownFlag) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json", "--bogus"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "", {"--bogus", "see calib-dlt --help"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, MissingOutputFlag) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "--output", {"required", "see calib-dlt --help"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, MissingInputArgument) {
  const auto r = Run("calib-dlt", {"-o", "out/camera.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "INPUT: ", {"give the correspondences file, or --target TARGET.json and the images"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, TwoInputArguments) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "in/volume.json", "-o", "out/camera.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "2 inputs: ", {"give one correspondences file, or --target TARGET.json before images"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, EmptyOutputName) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", ""});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "--output: ", {"must not be empty"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, BadSolverValue) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json", "--solver", "qr"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "--solver: ", {"qr", "normal-equations", "svd"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, SolverWithoutValue) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json", "--solver"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "--solver", {"see calib-dlt --help"}));
  EXPECT_TRUE(OutDirEmpty());
}

class CliCalibDltBadThreshold : public CliTest,
                                public ::testing::WithParamInterface<std::pair<std::string, std::string>> {};

TEST_P(CliCalibDltBadThreshold, IsRefused) {
  const auto& [flag, value] = GetParam();
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json", flag, value});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, flag + ": ",
                        {"expected a positive number, got \"" + value + "\"", "--help"}));
  EXPECT_LT(r.err.size(), 200u) << "the message should be short: " << r.err;
  EXPECT_TRUE(OutDirEmpty());
}

INSTANTIATE_TEST_SUITE_P(Values, CliCalibDltBadThreshold,
                         ::testing::Values(std::pair{"--min-extent-ratio", "-1"}, std::pair{"--min-extent-ratio", "0"},
                                           std::pair{"--min-extent-ratio", "abc"},
                                           std::pair{"--min-conditioning", "inf"},
                                           std::pair{"--min-conditioning", "nan"}),
                         [](const auto& param_info) {
                           std::string n = param_info.param.first.substr(2) + "_" + param_info.param.second;
                           for (char& ch : n) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
                           return n;
                         });

// ---------------------------------------------------------------------------------------------
// Success.

TEST_F(CliCalibDlt, HelpPrintsUsageOnStdout) {
  const auto r = Run("calib-dlt", {"--help"});
  EXPECT_EQ(r.exit_code, kOk);
  EXPECT_NE(r.out.find("Usage: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("calib-dlt"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--residuals"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Exit codes"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibDlt, VersionPrintsToolAndVersion) {
  const auto r = Run("calib-dlt", {"--version"});
  EXPECT_EQ(r.exit_code, kOk);
  EXPECT_EQ(r.out.rfind("calib-dlt ", 0), 0u) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST_F(CliCalibDlt, SolvesSynthCalibrationVolume) {
  Synth();
  const auto r = Run("calib-dlt", DltArgs("in/volume.json"));
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("wrote out/camera.json and out/residuals.json"), std::string::npos) << r.err;
  EXPECT_EQ(List("out"), (std::vector<std::string>{"camera.json", "residuals.json"}));  // no stray temporaries

  const Json camera = ReadJson("out/camera.json");
  EXPECT_EQ(camera.at("format"), "vstcal/camera@1");
  EXPECT_EQ(camera.at("method"), "dlt");
  EXPECT_EQ(camera.at("length_unit"), "mm");
  EXPECT_EQ(camera.at("image_size"), Json::array({640, 480}));
  // Exact data: the DLT recovers the synthetic camera.
  const Pinhole truth = Pinhole::FromTruth(ReadJson("in/volume.truth.json"));
  const Pinhole solved = Pinhole::FromTruth(camera);
  EXPECT_LT((solved.K - truth.K).cwiseAbs().maxCoeff(), 1e-6) << solved.K;
  EXPECT_LT((solved.R - truth.R).cwiseAbs().maxCoeff(), 1e-9) << solved.R;
  EXPECT_LT((solved.t - truth.t).cwiseAbs().maxCoeff(), 1e-6) << solved.t.transpose();
  EXPECT_EQ(camera.at("fit").at("n_points"), 60);
  EXPECT_LT(camera.at("fit").at("rms_px").get<double>(), 1e-6);
  EXPECT_EQ(camera.at("provenance").at("tool"), "calib-dlt");

  const Json residuals = ReadJson("out/residuals.json");
  EXPECT_EQ(residuals.at("format"), "vstcal/residuals@1");
  EXPECT_EQ(residuals.at("views").size(), 3u);
}

// Unrefined, the DLT camera is written as solved, so an absurd one is refused like an implausible
// refinement (docs/tools/calib-dlt.md#exit-codes): exit 3, one line, nothing written. 60 px of
// corner noise gives fx = 21 px (a pinhole 172° across); 30 px an RMS over 5 % of the image
// diagonal; 3 points per plane at 10 px an RMS of 8.8 px, under the RMS bound, with fy = 5.5 px
// (the DLT fits so few points closely, so the K is checked too). 10 px on all 60 points is noisy but
// a camera, and is written.
TEST_F(CliCalibDlt, UnrefinedImplausibleCameraWritesNothing) {
  const auto synth = [&](const std::string& noise) {
    return Synth("in/noisy.json", Override(Override(DefaultSynthArgs(), "--noise", noise), "--seed", "1"));
  };
  synth("60");
  EXPECT_TRUE(FailsWith(Run("calib-dlt", DltArgs("in/noisy.json")), "calib-dlt", kDegenerate, "in/noisy.json: ",
                        {"the dlt camera's focal lengths (fx 21.4 px", "pinhole field of view of 172.3 x",
                         "reprojection RMS 136.2 px over 60 points", "check that the points and pixels correspond"}));
  EXPECT_TRUE(OutDirEmpty());
  synth("30");
  EXPECT_TRUE(FailsWith(Run("calib-dlt", DltArgs("in/noisy.json")), "calib-dlt", kDegenerate, "in/noisy.json: ",
                        {"the dlt camera reprojects at an RMS of 46.7 px, more than 5 % of the image diagonal (40 px)"}));
  EXPECT_TRUE(OutDirEmpty());
  Json few = synth("10");
  for (Json& view : few["views"]) view["points"] = Json::array({view["points"][0], view["points"][9], view["points"][17]});
  WriteJson("in/few.json", few);
  EXPECT_TRUE(FailsWith(Run("calib-dlt", DltArgs("in/few.json")), "calib-dlt", kDegenerate, "in/few.json: ",
                        {"fy 5.488 px", "reprojection RMS 8.779 px over 9 points", "or add points"}));
  EXPECT_TRUE(OutDirEmpty());
  const CommandResult r = Run("calib-dlt", DltArgs("in/noisy.json"));
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_GT(ReadJson("out/camera.json").at("fit").at("rms_px").get<double>(), 10.0);
}

TEST_F(CliCalibDlt, SvdSolverAgrees) {
  Synth();
  ASSERT_EQ(Run("calib-dlt", {"in/volume.json", "-o", "out/ne.json"}).exit_code, kOk);
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/svd.json", "--solver", "svd"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json svd = ReadJson("out/svd.json");
  EXPECT_EQ(svd.at("dlt").at("solver"), "svd");
  EXPECT_LT((Pinhole::FromTruth(svd).K - Pinhole::FromTruth(ReadJson("out/ne.json")).K).cwiseAbs().maxCoeff(), 1e-6);
}

TEST_F(CliCalibDlt, QuietPrintsNothing) {
  Synth();
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json", "-q"});
  EXPECT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(List("out"), std::vector<std::string>{"camera.json"});
}

TEST_F(CliCalibDlt, RepeatedRunsGiveByteIdenticalFiles) {
  // Pixel noise makes the numbers non-trivial.
  Synth("in/volume.json", Override(DefaultSynthArgs(), "--noise", "0.3"));
  ASSERT_EQ(Run("calib-dlt", DltArgs("in/volume.json")).exit_code, kOk);
  const std::string camera = ReadText("out/camera.json"), residuals = ReadText("out/residuals.json");
  ASSERT_EQ(Run("calib-dlt", DltArgs("in/volume.json")).exit_code, kOk);
  EXPECT_EQ(ReadText("out/camera.json"), camera);
  EXPECT_EQ(ReadText("out/residuals.json"), residuals);
  EXPECT_EQ(List("out"), (std::vector<std::string>{"camera.json", "residuals.json"}));
}

TEST_F(CliCalibDlt, OutputIsAValidCameraForCalibSynth) {
  // The camera@1 file calib-dlt writes is read back by another tool.
  Synth();
  ASSERT_EQ(Run("calib-dlt", {"in/volume.json", "-o", "in/camera.json"}).exit_code, kOk);
  std::vector<std::string> args = Remove(Remove(DefaultSynthArgs(), "--image-size"), "--fx");
  args.insert(args.end(), {"--camera", "in/camera.json", "-o", "out/again.json"});
  const auto r = Run("calib-synth", args);
  EXPECT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(List("out"), (std::vector<std::string>{"again.json", "again.truth.json"}));
}

}  // namespace
}  // namespace vstcal::cli_test
