// CLI tests of calib-synth: bad flags and camera files get exit code 2, one line naming the flag
// (or file and field) and what to do, and neither the correspondences nor the truth file is
// written; good flags give valid, reproducible files.
#include <algorithm>
#include <cctype>
#include <ostream>

#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

using CliCalibSynth = CliTest;

struct BadFlags {
  std::string name;
  std::vector<std::string> args;  // everything but -o out/volume.json, which is appended
  std::string location;           // the flag (or file) the message must start with
  std::vector<std::string> phrases;
  bool add_output = true;
};

void PrintTo(const BadFlags& c, std::ostream* os) { *os << c.name; }

std::vector<std::string> Args(std::initializer_list<std::pair<std::string, std::string>> overrides,
                              std::initializer_list<std::string> removed = {}) {
  std::vector<std::string> args = DefaultSynthArgs();
  for (const std::string& flag : removed) args = Remove(args, flag, flag != "--no-test-points");
  for (const auto& [flag, value] : overrides) args = Override(args, flag, value);
  return args;
}

std::vector<BadFlags> BadFlagCases() {
  const std::string kWxH = "expected two positive integers as WxH";
  return {
      // The camera.
      {"ImageSizeWithoutHeight",
       Args({{"--image-size", "1280"}}),
       "--image-size: ",
       {kWxH, "got \"1280\"", "1280x720"}},
      {"ImageSizeZeroWidth", Args({{"--image-size", "0x720"}}), "--image-size: ", {kWxH, "got \"0x720\""}},
      {"ImageSizeNegative", Args({{"--image-size", "-640x480"}}), "--image-size: ", {kWxH}},
      {"ImageSizeLetters", Args({{"--image-size", "axb"}}), "--image-size: ", {kWxH, "got \"axb\""}},
      {"ImageSizeThreeNumbers", Args({{"--image-size", "640x480x3"}}), "--image-size: ", {kWxH}},
      {"ImageSizeFraction", Args({{"--image-size", "640.5x480"}}), "--image-size: ", {kWxH}},
      {"ImageSizeMissing", Args({}, {"--image-size"}), "--image-size: ", {"required without --camera", "1280x720"}},
      {"ImageSizeEmpty", Args({{"--image-size", ""}}), "--image-size: ", {"must not be empty"}},
      {"BothFxAndHfov", Args({{"--hfov-deg", "60"}}), "--fx/--hfov-deg: ", {"give exactly one of them"}},
      {"NeitherFxNorHfov", Args({}, {"--fx"}), "--fx/--hfov-deg: ", {"give exactly one of them"}},
      {"NegativeFx", Args({{"--fx", "-600"}}), "--fx/--fy/--hfov-deg: ", {"focal lengths must be positive"}},
      {"ZeroFy", Args({{"--fy", "0"}}), "--fx/--fy/--hfov-deg: ", {"focal lengths must be positive"}},
      {"FxNotANumber", Args({{"--fx", "six"}}), "", {"--fx", "six", "see calib-synth --help"}},
      {"FxInfinite", Args({{"--fx", "inf"}}), "--fx: ", {"must be a finite number, got inf"}},
      {"CxNaN", Args({{"--cx", "nan"}}), "--cx: ", {"must be a finite number, got nan"}},
      {"HfovStraightAngle",
       Args({{"--hfov-deg", "180"}}, {"--fx"}),
       "--hfov-deg: ",
       {"must lie in (0, 180)", "got 180"}},
      {"HfovNegative", Args({{"--hfov-deg", "-10"}}, {"--fx"}), "--hfov-deg: ", {"must lie in (0, 180)", "got -10"}},
      {"SkewZero", Args({{"--skew-deg", "0"}}), "--skew-deg: ", {"must lie in (0, 180)", "90 means no skew"}},
      {"DistortionFourNumbers",
       Args({{"--distortion", "0.1,0.2,0,0"}}),
       "--distortion: ",
       {"expected 5 numbers k1,k2,p1,p2,k3"}},
      {"DistortionLetter",
       Args({{"--distortion", "0.1,a,0,0,0"}}),
       "--distortion: ",
       {"expected a number, got \"a\""}},
      {"DistortionTrailingGarbage",
       Args({{"--distortion", "0.1,0.1x,0,0,0"}}),
       "--distortion: ",
       {"expected a number, got \"0.1x\""}},
      {"DistortionNaN", Args({{"--distortion", "0,nan,0,0,0"}}), "--distortion: ", {"must be a finite number, got nan"}},
      {"DistortionEmptyItem", Args({{"--distortion", "0,,0,0,0"}}), "--distortion: ", {"expected 5 numbers", "got 4"}},
      {"DistortionEmpty", Args({{"--distortion", ""}}), "--distortion: ", {"expected a number, got \"\""}},
      {"CameraFileMissing",
       Args({{"--camera", "in/missing.json"}}, {"--image-size", "--fx"}),
       "in/missing.json: ",
       {"no such file", "check the path"}},
      {"CameraFileIsADirectory", Args({{"--camera", "in"}}, {"--image-size", "--fx"}), "in: ", {"is a directory"}},
      {"CameraWithFx",
       Args({{"--camera", "in/missing.json"}}, {"--image-size"}),
       "--camera excludes --fx",
       {"see calib-synth --help"}},
      {"CameraWithDistortion",
       Args({{"--camera", "in/missing.json"}, {"--distortion", "0,0,0,0,0"}}, {"--image-size", "--fx"}),
       "--camera excludes --distortion",
       {"see calib-synth --help"}},

      // The volume.
      {"NegativeNoise", Args({{"--noise", "-1"}}), "--noise: ", {"must not be negative, got -1"}},
      {"FarBeforeNear", Args({{"--near", "400"}, {"--far", "0"}}), "--far: ", {"must not be less than --near"}},
      {"NearNaN", Args({{"--near", "nan"}}), "--near: ", {"must be a finite number"}},
      {"RollNaN", Args({{"--roll-deg", "nan"}}), "--roll-deg: ", {"must be a finite number"}},
      {"ZeroInterval", Args({{"--interval", "0"}}), "--interval: ", {"must be positive, got 0"}},
      {"TooManyPlanes", Args({{"--interval", "0.01"}}), "--interval: ", {"more than the 10000 views a file may hold", "use a larger interval"}},
      {"ZeroSpacing", Args({{"--spacing", "0"}}), "--spacing: ", {"must be positive, got 0"}},
      {"ZeroCameraDistance", Args({{"--camera-distance", "0"}}), "--camera-distance: ", {"must be positive, got 0"}},
      {"CameraInsideTheVolume",
       Args({{"--grid", "13x9"}, {"--camera-distance", "100"}, {"--tilt-deg", "70"}}),
       "--camera-distance: ",
       {"the camera sits inside the volume", "move it back"}},
      {"TiltTooLarge", Args({{"--tilt-deg", "85"}}), "--tilt-deg: ", {"within ±80°"}},
      {"NoCornerVisible",
       Args({{"--hfov-deg", "0.5"}}, {"--fx"}),
       "--camera-distance/--tilt-deg: ",
       {"no corner is visible", "point the camera at the template"}},
      {"TestPointNotVisible",
       Args({{"--hfov-deg", "10"}}, {"--fx", "--no-test-points"}),
       "test point \"Left\"",
       {"is not visible", "widen the field of view"}},
      {"GridTooSmall", Args({{"--grid", "1x4"}}), "--grid: ", {"at least 2×2 corners"}},
      {"GridMalformed", Args({{"--grid", "5by4"}}), "--grid: ", {"expected two positive integers", "got \"5by4\""}},
      {"UnknownLengthUnit",
       Args({{"--length-unit", "inch"}}),
       "--length-unit: ",
       {"inch", "mm", "see calib-synth --help"}},
      {"NegativeSeed", Args({{"--seed", "-1"}}), "--seed: ", {"expected a whole number", "got \"-1\""}},
      {"SeedOverflow", Args({{"--seed", "18446744073709551616"}}), "--seed: ", {"expected a whole number"}},

      // Usage and outputs.
      {"UnknownFlag", Args({{"--bogus", "1"}}), "", {"--bogus", "see calib-synth --help"}},
      {"MissingOutput", Args({}), "--output", {"required", "see calib-synth --help"}, false},
      {"EmptyOutputName", Args({{"-o", ""}}), "--output: ", {"must not be empty"}, false},
      {"OutputDirectoryMissing",
       Args({{"-o", "out/missing/volume.json"}}),
       "out/missing/volume.json: ",
       {"directory out/missing does not exist", "create it first"},
       false},
      {"TruthDirectoryMissing",
       Args({{"--truth", "out/missing/truth.json"}}),
       "out/missing/truth.json: ",
       {"directory out/missing does not exist", "create it first"}},
      {"TruthIsTheOutput",
       Args({{"--truth", "out/volume.json"}}),
       "out/volume.json: ",
       {"the same file is given for two outputs", "give each output its own file name"}},
  };
}

class CliCalibSynthBadFlags : public CliTest, public ::testing::WithParamInterface<BadFlags> {};

TEST_P(CliCalibSynthBadFlags, FailsWithOneActionableLineAndNoOutput) {
  const BadFlags& c = GetParam();
  std::vector<std::string> args = c.args;
  if (c.add_output) args.insert(args.end(), {"-o", "out/volume.json"});
  const auto r = Run("calib-synth", args);
  EXPECT_TRUE(FailsWith(r, "calib-synth", kBadInput, c.location, c.phrases));
  EXPECT_TRUE(OutDirEmpty());
}

INSTANTIATE_TEST_SUITE_P(Cases, CliCalibSynthBadFlags, ::testing::ValuesIn(BadFlagCases()),
                         [](const auto& param_info) { return param_info.param.name; });

// --camera with a file that is not a valid camera@1.
struct BadCameraFile {
  std::string name;
  std::string location;  // after "in/camera.json: "
  std::vector<std::string> phrases;
  std::function<void(Json& camera)> edit;
};

void PrintTo(const BadCameraFile& c, std::ostream* os) { *os << c.name; }

class CliCalibSynthBadCameraFile : public CliTest, public ::testing::WithParamInterface<BadCameraFile> {};

TEST_P(CliCalibSynthBadCameraFile, IsRefusedWithFileAndField) {
  const BadCameraFile& c = GetParam();
  Synth();
  Json camera = ReadJson("in/volume.truth.json");
  c.edit(camera);
  WriteJson("in/camera.json", camera);
  std::vector<std::string> args = Remove(Remove(DefaultSynthArgs(), "--image-size"), "--fx");
  args.insert(args.end(), {"--camera", "in/camera.json", "-o", "out/volume.json"});
  const auto r = Run("calib-synth", args);
  EXPECT_TRUE(FailsWith(r, "calib-synth", kBadInput, "in/camera.json: " + c.location, c.phrases));
  EXPECT_TRUE(OutDirEmpty());
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliCalibSynthBadCameraFile,
    ::testing::Values(
        BadCameraFile{"CorrespondencesInstead",
                      "format: ",
                      {"this is a \"vstcal/correspondences@1\" file", "expected \"vstcal/camera@1\""},
                      [](Json& c) { c["format"] = "vstcal/correspondences@1"; }},
        BadCameraFile{"MissingLengthUnit",
                      "length_unit: ",
                      {"missing field", "add \"length_unit\""},
                      [](Json& c) { c.erase("length_unit"); }},
        BadCameraFile{"KNotUpperTriangular",
                      "K: ",
                      {"upper triangular", "[[fx, s, cx], [0, fy, cy], [0, 0, 1]]"},
                      [](Json& c) { c["K"][1][0] = 1.0; }},
        BadCameraFile{
            "NegativeFocalLength", "K: ", {"fx and fy must be positive"}, [](Json& c) { c["K"][0][0] = -600.0; }},
        BadCameraFile{"KWithTwoRows", "K: ", {"expected 3 items, got 2"}, [](Json& c) { c["K"].erase(2); }},
        BadCameraFile{"IntrinsicsDisagreeWithK",
                      "intrinsics: ",
                      {"disagrees with K", "make it match K"},
                      [](Json& c) { c["intrinsics"]["fu"] = 700.0; }},
        BadCameraFile{"UnknownDistortionModel",
                      "distortion.model: ",
                      {"unknown distortion model \"fisheye\""},
                      [](Json& c) { c["distortion"]["model"] = "fisheye"; }},
        BadCameraFile{"NotARotation",
                      "camera_from_world.R: ",
                      {"not a rotation matrix"},
                      [](Json& c) { c["camera_from_world"]["R"][0][0] = 2.0; }},
        BadCameraFile{"PDisagreesWithPose",
                      "P: ",
                      {"disagrees with K [R | t]"},
                      [](Json& c) {
                        c["P"] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
                      }}),
    [](const auto& param_info) { return param_info.param.name; });

TEST_F(CliCalibSynth, CameraFileWithNaNLiteral) {
  Synth();
  std::string text = ReadText("in/volume.truth.json");
  const size_t at = text.find("600.0");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 5, "NaN");
  WriteText("in/camera.json", text);
  std::vector<std::string> args = Remove(Remove(DefaultSynthArgs(), "--image-size"), "--fx");
  args.insert(args.end(), {"--camera", "in/camera.json", "-o", "out/volume.json"});
  const auto r = Run("calib-synth", args);
  EXPECT_TRUE(FailsWith(r, "calib-synth", kBadInput, "in/camera.json: " + LineColumn(text, at) + ": ",
                        {"'NaN' is not a JSON number"}));
  EXPECT_TRUE(OutDirEmpty());
}

// ---------------------------------------------------------------------------------------------
// Success.

TEST_F(CliCalibSynth, HelpPrintsUsageOnStdout) {
  const auto r = Run("calib-synth", {"--help"});
  EXPECT_EQ(r.exit_code, kOk);
  EXPECT_NE(r.out.find("Usage: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--hfov-deg"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibSynth, VersionPrintsToolAndVersion) {
  const auto r = Run("calib-synth", {"--version"});
  EXPECT_EQ(r.exit_code, kOk);
  EXPECT_EQ(r.out.rfind("calib-synth ", 0), 0u) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST_F(CliCalibSynth, NegativeDistortionCoefficientsAreValues) {
  // "-0.1,..." after --distortion is its value, not an unknown flag; and so is "=-0.1,...".
  for (const std::string form : {"separate", "equals"}) {
    std::vector<std::string> args = DefaultSynthArgs();
    if (form == "separate") {
      args.insert(args.end(), {"--distortion", "-0.1,0.01,0,0,-0.001"});
    } else {
      args.push_back("--distortion=-0.1,0.01,0,0,-0.001");
    }
    args.insert(args.end(), {"-o", "out/volume.json"});
    const auto r = Run("calib-synth", args);
    ASSERT_EQ(r.exit_code, kOk) << form << ": " << r.err;
    const Json distortion = ReadJson("out/volume.truth.json").at("distortion");
    EXPECT_EQ(distortion.at("model"), "radial-tangential");
    EXPECT_EQ(distortion.at("k1"), -0.1);
    EXPECT_EQ(distortion.at("k3"), -0.001);
  }
}

TEST_F(CliCalibSynth, WritesVolumeAndTruthBesideIt) {
  std::vector<std::string> args = DefaultSynthArgs();
  args.insert(args.end(), {"-o", "out/volume.json"});
  const auto r = Run("calib-synth", args);
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "calib-synth: 60 points in 3 views, 0 test points; wrote out/volume.json and out/volume.truth.json\n");
  EXPECT_EQ(List("out"), (std::vector<std::string>{"volume.json", "volume.truth.json"}));

  const Json volume = ReadJson("out/volume.json");
  EXPECT_EQ(volume.at("format"), "vstcal/correspondences@1");
  EXPECT_EQ(volume.at("rig"), "volume");
  EXPECT_EQ(volume.at("views").size(), 3u);
  EXPECT_EQ(volume.at("provenance").at("tool"), "calib-synth");
  const Json truth = ReadJson("out/volume.truth.json");
  EXPECT_EQ(truth.at("format"), "vstcal/camera@1");
  EXPECT_EQ(truth.at("method"), "synthetic");
}

TEST_F(CliCalibSynth, TestPointsAndExplicitTruthPath) {
  std::vector<std::string> args = Remove(DefaultSynthArgs(), "--no-test-points", false);
  args.insert(args.end(), {"--hfov-deg", "90", "-o", "out/v.json", "--truth", "out/t.json"});
  args = Remove(args, "--fx");
  const auto r = Run("calib-synth", args);
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(List("out"), (std::vector<std::string>{"t.json", "v.json"}));
  EXPECT_EQ(ReadJson("out/v.json").at("test_points").size(), 5u);
}

TEST_F(CliCalibSynth, SameSeedGivesByteIdenticalFiles) {
  std::vector<std::string> args = Override(Override(DefaultSynthArgs(), "--noise", "0.5"), "--seed", "42");
  args.insert(args.end(), {"-o", "out/volume.json"});
  ASSERT_EQ(Run("calib-synth", args).exit_code, kOk);
  const std::string volume = ReadText("out/volume.json"), truth = ReadText("out/volume.truth.json");
  ASSERT_EQ(Run("calib-synth", args).exit_code, kOk);
  EXPECT_EQ(ReadText("out/volume.json"), volume);
  EXPECT_EQ(ReadText("out/volume.truth.json"), truth);
  // The noise is really there: another seed gives other pixels.
  ASSERT_EQ(Run("calib-synth", Override(args, "--seed", "43")).exit_code, kOk);
  EXPECT_NE(ReadText("out/volume.json"), volume);
}

TEST_F(CliCalibSynth, ThenCalibDltSucceeds) {
  std::vector<std::string> args = Override(DefaultSynthArgs(), "--noise", "0.2");
  args = Remove(args, "--no-test-points", false);
  args = Override(Override(args, "--grid", "9x7"), "--far", "1000");
  args.insert(args.end(), {"-o", "in/volume.json"});
  args = Override(args, "--camera-distance", "2500");
  ASSERT_EQ(Run("calib-synth", args).exit_code, kOk);
  const auto r = Run("calib-dlt", {"in/volume.json", "-o", "out/camera.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json camera = ReadJson("out/camera.json");
  EXPECT_EQ(camera.at("format"), "vstcal/camera@1");
  EXPECT_NEAR(camera.at("K")[0][0].get<double>(), 600, 10);
  EXPECT_NEAR(camera.at("K")[1][2].get<double>(), 239.5, 10);
  EXPECT_EQ(camera.at("fit").at("test_points").size(), 5u);
  EXPECT_EQ(List("out"), std::vector<std::string>{"camera.json"});
}

}  // namespace
}  // namespace vstcal::cli_test
