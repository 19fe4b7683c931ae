// Bounded work and strict input (docs/reliability.md#limits): no input or size flag can crash a tool,
// hang it or exhaust the machine. Each case was a crash, a hang, a silent acceptance or a
// misleading message before; each now gets exit code 2, one line naming the file (or flag), the
// field and the fix, and no output file.
#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

using CliLimits = CliTest;

// A YAML file nested 50,000 levels deep (100 KB) overflowed the stack inside cv::FileStorage.
TEST_F(CliLimits, DeeplyNestedYamlIsRefused) {
  for (const auto& [name, text] :
       {std::pair<std::string, std::string>{"flow", "%YAML:1.0\n---\na: " + std::string(50000, '[') + "\n"},
        {"block", "%YAML:1.0\n---\na:\n" + [] {
           std::string s;
           for (int i = 0; i < 50000; ++i) s += "- ";
           return s + "x\n";
         }()}}) {
    WriteText("in/deep.yaml", text);
    const CommandResult r = Run("calib-convert", {"in/deep.yaml", "-o", "out/c.json"});
    EXPECT_TRUE(FailsWith(r, "calib-convert", kBadInput, "in/deep.yaml: line ", {"nested too deeply"})) << name;
    EXPECT_TRUE(OutDirEmpty());
  }
}

// 16 bytes on which cv::FileStorage 4.6 loops forever (found by libFuzzer, docs/reliability.md#fuzzing);
// the ctest timeout would end this test if it still hung.
TEST_F(CliLimits, YamlThatHangsOpenCvIsRefused) {
  WriteText("in/hang.yaml", "%YAML:1.0\n -a\n:\n-");
  const CommandResult r = Run("calib-convert", {"in/hang.yaml", "-o", "out/c.json"});
  EXPECT_TRUE(FailsWith(r, "calib-convert", kBadInput, "in/hang.yaml: line 2, column 2: ", {"the top level is indented"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliLimits, DeeplyNestedJsonAndCameramodelAreRefused) {
  WriteText("in/deep.json", "{\"a\": " + std::string(50000, '[') + "\n");
  CommandResult r = Run("calib-convert", {"in/deep.json", "-o", "out/c.yaml"});
  EXPECT_TRUE(FailsWith(r, "calib-convert", kBadInput, "in/deep.json: line 1, column ", {"nested more than 64 levels"}));
  WriteText("in/deep.cameramodel", "{'a': " + std::string(50000, '[') + "\n");
  r = Run("calib-convert", {"in/deep.cameramodel", "-o", "out/c.json"});
  EXPECT_TRUE(
      FailsWith(r, "calib-convert", kBadInput, "in/deep.cameramodel: line 1, column ", {"nested more than 64 levels"}));
  EXPECT_TRUE(OutDirEmpty());
}

// A file without end (a device) or beyond the size limit is refused, not read into memory.
TEST_F(CliLimits, EndlessInputIsRefused) {
  // Refused before it is opened, not read to the 256 MiB limit first (issue 24: 530 MB, 4–6 s).
  const CommandResult r = Run("calib-dlt", {"/dev/zero", "-o", "out/c.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "/dev/zero: ", {"is not a regular file (a device, a pipe or a socket)"}));
  EXPECT_TRUE(OutDirEmpty());
}

// A key given twice was accepted silently, the last one winning.
TEST_F(CliLimits, DuplicateJsonKeysAreRefusedWithLineAndKey) {
  const Json volume = Synth("in/volume.json");
  std::string text = volume.dump(2);
  const std::string first = "\"image_size\": [\n    640,\n    480\n  ],\n";
  const size_t at = text.find(first);
  ASSERT_NE(at, std::string::npos);
  text.insert(at + first.size(), "  \"image_size\": [1280, 720],\n");
  WriteText("in/dup.json", text);
  CommandResult r = Run("calib-dlt", {"in/dup.json", "-o", "out/c.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "in/dup.json: " + LineColumn(text, at + first.size() + 2) + ": ",
                        {"duplicate key \"image_size\" in the top-level object", "keep one of them"}));

  // Nested: the object's path is named.
  text = volume.dump(2);
  const size_t name = text.find("\"name\": \"plane-01\"");
  ASSERT_NE(name, std::string::npos);
  text.insert(name, "\"name\": \"plane-09\", ");
  WriteText("in/dup.json", text);
  r = Run("calib-tsai", {"in/dup.json", "-o", "out/c.json"});
  EXPECT_TRUE(FailsWith(r, "calib-tsai", kBadInput, "in/dup.json: " + LineColumn(text, name + 20) + ": ",
                        {"duplicate key \"name\" in views[1]"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliLimits, DuplicateKeyInACameraAndInAChain) {
  Synth("in/volume.json");
  std::string camera = ReadText("in/volume.truth.json");
  camera.insert(camera.find("\"length_unit\""), "\"length_unit\": \"m\",\n  ");
  WriteText("in/camera.json", camera);
  CommandResult r = Run("calib-convert", {"in/camera.json", "-o", "out/c.yaml"});
  EXPECT_TRUE(FailsWith(r, "calib-convert", kBadInput, "in/camera.json: line ", {"duplicate key \"length_unit\""}));

  // A chain that names one error term twice dropped the first silently.
  WriteText("in/chain.json", R"({"format": "vstcal/vst-chain@1", "sources": {"tracking": {
    "latency_s": {"distribution": "fixed", "value": 0.01}, "latency_s": {"distribution": "fixed", "value": 0.02}}}})");
  r = Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json"});
  EXPECT_TRUE(FailsWith(r, "err-sim", kBadInput, "in/chain.json: line 2, column ",
                        {"duplicate key \"latency_s\" in sources.tracking"}));
  EXPECT_TRUE(OutDirEmpty());
}

// An image size of 1e10 said "expected an integer".
TEST_F(CliLimits, ImageSizeBeyondTheLimitSaysSo) {
  Json volume = Synth("in/volume.json");
  volume["image_size"][0] = 1e10;
  WriteJson("in/big.json", volume);
  CommandResult r = Run("calib-dlt", {"in/big.json", "-o", "out/c.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "in/big.json: image_size[0]: ",
                        {"10000000000 px is more than the 1000000 px per side vstcal accepts",
                         "give the image width in pixels"}));
  r = Run("calib-synth", {"--image-size", "10000000000x480", "--fx", "500", "-o", "out/v.json"});
  EXPECT_TRUE(FailsWith(r, "calib-synth", kBadInput, "--image-size: ", {"exceeds the largest side", "1000000"}));
  EXPECT_TRUE(OutDirEmpty());
}

// --grid-size 100000x100000 hung computing ten billion ellipses.
TEST_F(CliLimits, UncertaintyGridIsBounded) {
  Synth("in/volume.json");
  CommandResult r = Run("calib-tsai", {"in/volume.json", "-o", "out/c.json", "--uncertainty-grid", "1500",
                                       "--grid-size", "100000x100000"});
  EXPECT_TRUE(FailsWith(r, "calib-tsai", kBadInput, "--grid-size: ",
                        {"10000000000 cells, more than the 1000000", "give a coarser grid"}));
  r = Run("calib-dlt", {"in/volume.json", "-o", "out/c.json", "--refine", "--uncertainty-grid", "1500",
                        "--grid-size", "99999999999999999999x2"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "--grid-size: ", {"exceeds the largest side"}));
  EXPECT_TRUE(OutDirEmpty());
}

// --grid-size without --uncertainty-grid was ignored silently.
TEST_F(CliLimits, GridSizeWithoutUncertaintyGridIsRefused) {
  Synth("in/volume.json");
  for (const std::string tool : {"calib-tsai", "calib-dlt"}) {
    std::vector<std::string> args = {"in/volume.json", "-o", "out/c.json", "--grid-size", "8x6"};
    if (tool == "calib-dlt") args.push_back("--refine");
    const CommandResult r = Run(tool, args);
    EXPECT_TRUE(FailsWith(r, tool, kBadInput, "--grid-size", {"requires --uncertainty-grid"}));
  }
  EXPECT_TRUE(OutDirEmpty());
}

// calib-synth --grid 100000x100000 took 12 GB; a tiny interval asked for 1e300 planes; a camera
// 1e308 away wrote null into P.
TEST_F(CliLimits, SyntheticSceneIsBounded) {
  auto synth = [&](const std::string& flag, const std::string& value) {
    std::vector<std::string> args = Override(DefaultSynthArgs(), flag, value);
    args.insert(args.end(), {"-o", "out/v.json"});
    return Run("calib-synth", args);
  };
  EXPECT_TRUE(FailsWith(synth("--grid", "100000x100000"), "calib-synth", kBadInput, "--grid: ",
                        {"100000×100000 corners on 3 planes", "more than the 1000000", "use fewer corners"}));
  EXPECT_TRUE(FailsWith(synth("--interval", "1e-300"), "calib-synth", kBadInput, "--interval: ",
                        {"template positions, more than the 10000", "use a larger interval"}));
  EXPECT_TRUE(FailsWith(synth("--camera-distance", "1e308"), "calib-synth", kBadInput, "--camera-distance: ",
                        {"1e+308 is beyond ±1e+09", "give a realistic value"}));
  EXPECT_TRUE(FailsWith(synth("--fx", "1e300"), "calib-synth", kBadInput, "--fx: ", {"beyond ±1e+09"}));
  std::vector<std::string> planar = {"--rig", "planar-views", "--image-size", "640x480", "--fx", "500",
                                     "--views", "20000", "-o", "out/v.json"};
  EXPECT_TRUE(FailsWith(Run("calib-synth", planar), "calib-synth", kBadInput, "--views: ", {"give 1 to 10000 views"}));
  EXPECT_TRUE(OutDirEmpty());
}

// Noise-free data fit exactly: every rounding-size residual was listed as an outlier of infinite
// sigma, written as null. No non-finite number reaches a file now (docs/reliability.md#non-finite).
TEST_F(CliLimits, NoiseFreeRefinementListsNoOutlier) {
  Synth("in/volume.json");  // no noise
  const CommandResult r = Run("calib-dlt", {"in/volume.json", "-o", "out/c.json", "--refine", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(r.err, "");
  const Json camera = ReadJson("out/c.json");
  EXPECT_TRUE(camera["refinement"]["outliers"].empty()) << camera["refinement"].dump();
  EXPECT_EQ(camera["refinement"].dump().find("null"), std::string::npos) << camera["refinement"].dump();
}

// Flags that did nothing in the presence of others passed silently.
TEST_F(CliLimits, FlagsThatWouldDoNothingAreRefused) {
  Synth("in/volume.json");
  CommandResult r = Run("calib-tsai", {"in/volume.json", "-o", "out/c.json", "--loss-scale", "2"});
  EXPECT_TRUE(FailsWith(r, "calib-tsai", kBadInput, "--loss-scale: ", {"--loss huber or --loss cauchy"}));
  r = Run("calib-tsai", {"in/volume.json", "-o", "out/c.json", "--sx", "1.01"});  // three planes: not coplanar
  EXPECT_TRUE(FailsWith(r, "calib-tsai", kBadInput, "--sx: ", {"not coplanar", "--variant coplanar"}));
  r = Run("calib-convert", {"in/volume.truth.json", "-o", "out/c.yaml", "--to", "mrcal"});
  EXPECT_TRUE(FailsWith(r, "calib-convert", kBadInput, "--to: ", {"out/c.yaml", "OpenCV FileStorage YAML"}));
  EXPECT_TRUE(OutDirEmpty());
}

}  // namespace
}  // namespace vstcal::cli_test
