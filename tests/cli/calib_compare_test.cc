// CLI tests of calib-compare: two cameras in, a comparison on stdout; bad files and mismatched
// sensors give exit code 2 with one line naming the files.
#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

using CliCalibCompare = CliTest;

TEST_F(CliCalibCompare, TruthAgainstItselfAgreesExactly) {
  Synth();
  const CommandResult r = Run("calib-compare", {"in/volume.truth.json", "in/volume.truth.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.out.find("RMS 0.0000 px, max 0.0000 px over 81 grid points"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rotation difference      0.000000 deg"), std::string::npos) << r.out;
}

TEST_F(CliCalibCompare, EstimateAgainstTruth) {
  Synth();
  ASSERT_EQ(Run("calib-dlt", {"in/volume.json", "-o", "out/cam.json", "-q"}).exit_code, kOk);
  const CommandResult r = Run("calib-compare", {"in/volume.truth.json", "out/cam.json", "--depth", "1700"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.out.find("pixel disagreement at depth 1700.0 mm"), std::string::npos) << r.out;
}

// --test-points: the default volume's calibration points are three 5 × 4 grids at z = 0, 200, 400
// spanning x ∈ [−200, 200], y ∈ [−150, 150], so their convex hull is that box: calib-synth's test
// points Left (x = −640) and Right (x = 360) lie outside it, the three Middle ones inside. The
// truth against itself disagrees by 0 px everywhere.
TEST_F(CliCalibCompare, TestPointsInsideAndOutsideTheConvexHull) {
  Synth("in/volume.json", Remove(DefaultSynthArgs(), "--no-test-points", false));
  const CommandResult r =
      Run("calib-compare", {"in/volume.truth.json", "in/volume.truth.json", "--test-points", "in/volume.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  for (const char* line : {"Left           outside  0.0000", "Right          outside  0.0000",
                           "Middle 1       inside   0.0000", "Middle 2       inside   0.0000",
                           "Middle 3       inside   0.0000"}) {
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  }
}

// One plane of calibration points spans no volume: no test point is inside or outside.
TEST_F(CliCalibCompare, TestPointsOfOnePlaneHaveNoSide) {
  Synth("in/plane.json", Override(Remove(DefaultSynthArgs(), "--no-test-points", false), "--far", "0"));
  const CommandResult r =
      Run("calib-compare", {"in/plane.truth.json", "in/plane.truth.json", "--test-points", "in/plane.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.out.find("Middle 1       no hull  0.0000"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("inside"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("outside"), std::string::npos) << r.out;
}

TEST_F(CliCalibCompare, TestPointsFileWithoutTestPoints) {
  Synth();
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/volume.truth.json", "in/volume.truth.json", "--test-points",
                                              "in/volume.json"}),
                        "calib-compare", kBadInput, "in/volume.json: test_points: ", {"none", "give a file with test points"}));
}

// A camera calibrated from planar views has no world pose: no comparison at world points, and
// nothing printed before the refusal.
TEST_F(CliCalibCompare, TestPointsNeedBothCamerasPosedInTheWorld) {
  Synth("in/volume.json", Remove(DefaultSynthArgs(), "--no-test-points", false));
  Synth("in/planar.json", {"--rig", "planar-views", "--image-size", "640x480", "--fx", "600", "--grid", "5x4",
                           "--spacing", "30", "--views", "4"});
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/planar.truth.json", "in/volume.truth.json", "--test-points",
                                              "in/volume.json"}),
                        "calib-compare", kBadInput, "in/volume.truth.json vs in/planar.truth.json: camera_from_world: ",
                        {"posed in the world"}));
}

TEST_F(CliCalibCompare, MissingFile) {
  Synth();
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/volume.truth.json", "in/nope.json"}), "calib-compare", kBadInput,
                        "in/nope.json: ", {"no such file", "check the path"}));
}

TEST_F(CliCalibCompare, CorrespondencesInsteadOfCamera) {
  Synth();
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/volume.truth.json", "in/volume.json"}), "calib-compare", kBadInput,
                        "in/volume.json: format: ", {"vstcal/correspondences@1", "expected \"vstcal/camera@1\""}));
}

TEST_F(CliCalibCompare, DifferentSensors) {
  Synth();
  Synth("in/other.json", Override(DefaultSynthArgs(), "--image-size", "800x600"));
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/volume.truth.json", "in/other.truth.json"}), "calib-compare",
                        kBadInput, "in/other.truth.json vs in/volume.truth.json: image_size: ",
                        {"640x480 vs 800x600", "same sensor"}));
}

TEST_F(CliCalibCompare, NonPositiveDepth) {
  Synth();
  const CommandResult r = Run("calib-compare", {"in/volume.truth.json", "in/volume.truth.json", "--depth", "-5"});
  EXPECT_TRUE(FailsWith(r, "calib-compare", kBadInput, "--depth", {}));
}

// --- Thresholds for CI: --max-px, --max-sigma, --junit ---------------------------------------------

// A 1280×720 pinhole with fx = fy = 1000 and the principal point (cx, 360), 2 m in front of the
// world origin; with σ > 0 a covariance of cx and cy, each σ² and uncorrelated.
Json CheckCamera(double cx, double sigma) {
  Json c;
  c["format"] = "vstcal/camera@1";
  c["image_size"] = {1280, 720};
  c["length_unit"] = "mm";
  c["method"] = "hand";
  c["K"] = {{1000.0, 0.0, cx}, {0.0, 1000.0, 360.0}, {0.0, 0.0, 1.0}};
  c["distortion"] = {{"model", "none"}};
  c["camera_from_world"] = {{"R", {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}}, {"t", {0.0, 0.0, 2000.0}}};
  if (sigma > 0) c["covariance"] = {{"parameters", {"cx", "cy"}}, {"matrix", {{sigma * sigma, 0.0}, {0.0, sigma * sigma}}}};
  return c;
}

// The principal points 1.5 px apart: every grid point disagrees by exactly 1.5 px. Each camera knows
// cx and cy to σ = 0.5 px, so the difference has σ = √(0.25 + 0.25) = 0.707 px per axis and is
// 1.5/0.707 = 2.12 σ: beyond a 1 px bound, but within what the two calibrations' noise explains.
TEST_F(CliCalibCompare, MaxPxAndMaxSigmaOnAPrincipalPointShift) {
  WriteJson("in/a.json", CheckCamera(640, 0.5));
  WriteJson("in/b.json", CheckCamera(641.5, 0.5));
  CommandResult r = Run("calib-compare", {"in/a.json", "in/b.json", "--max-px", "2"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.out.find("check grid px: pass: max over 81 grid points: 1.5000 px ≤ limit 2 px"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("checks: 1, failed 0\n"), std::string::npos) << r.out;

  r = Run("calib-compare", {"in/a.json", "in/b.json", "--max-px", "1"});
  EXPECT_EQ(r.exit_code, kCheckFailed) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find("check grid px: fail: max over 81 grid points: 1.5000 px > limit 1 px"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("checks: 1, failed 1 (exit code 4)"), std::string::npos) << r.out;

  r = Run("calib-compare", {"in/a.json", "in/b.json", "--max-sigma", "3"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.out.find("check grid sigma: pass: max over 81 grid points: 2.1213 σ ≤ limit 3 σ"), std::string::npos) << r.out;

  r = Run("calib-compare", {"in/a.json", "in/b.json", "--max-sigma", "2"});
  EXPECT_EQ(r.exit_code, kCheckFailed) << r.err;
  EXPECT_NE(r.out.find("check grid sigma: fail: max over 81 grid points: 2.1213 σ > limit 2 σ"), std::string::npos) << r.out;

  // Both, with JUnit: two testcases, the pixel bound failed.
  r = Run("calib-compare", {"in/a.json", "in/b.json", "--max-px", "1", "--max-sigma", "3", "--junit", "out/compare.xml"});
  EXPECT_EQ(r.exit_code, kCheckFailed) << r.err;
  EXPECT_EQ(JUnitCounts(Path("out/compare.xml")), "2 1 1\n");
  EXPECT_NE(ReadText("out/compare.xml").find("<testcase classname=\"calib-compare\" name=\"grid sigma\">"), std::string::npos);
}

// Two DLT refinements of one volume with independent pixel noise: their disagreement at the grid
// and at the test points is what their covariances predict — within 5 σ everywhere — while a
// pixel bound far below the noise fails at every test point. The template (9×7 at 100 mm, 1.5 m
// away) covers most of the image: the covariances are first-order, and far outside the points
// (the default 5×4 template covers a sixth of the image) the distortion's extrapolation is not
// linear in the noise — there two such calibrations were seen 6.1 σ apart at a corner.
TEST_F(CliCalibCompare, TwoNoisyCalibrationsAgreeWithinTheirCovariances) {
  std::vector<std::string> args =
      Override(Override(Remove(DefaultSynthArgs(), "--no-test-points", false), "--noise", "0.3"), "--grid", "9x7");
  Synth("in/one.json", Override(args, "--seed", "1"));
  Synth("in/two.json", Override(args, "--seed", "2"));
  ASSERT_EQ(Run("calib-dlt", {"in/one.json", "-o", "out/one.cam.json", "--refine", "-q"}).exit_code, kOk);
  ASSERT_EQ(Run("calib-dlt", {"in/two.json", "-o", "out/two.cam.json", "--refine", "-q"}).exit_code, kOk);
  CommandResult r = Run("calib-compare", {"out/one.cam.json", "out/two.cam.json", "--test-points", "in/one.json",
                                          "--max-sigma", "5", "--junit", "out/sigma.xml"});
  ASSERT_EQ(r.exit_code, kOk) << r.out << r.err;
  for (const char* name : {"grid sigma: pass", "test point Left sigma: pass", "test point Middle 2 sigma: pass"}) {
    EXPECT_NE(r.out.find(std::string("check ") + name), std::string::npos) << name << "\n" << r.out;
  }
  EXPECT_EQ(JUnitCounts(Path("out/sigma.xml")), "6 0 0\n");
  r = Run("calib-compare", {"out/one.cam.json", "out/two.cam.json", "--test-points", "in/one.json", "--max-px", "0.0001"});
  EXPECT_EQ(r.exit_code, kCheckFailed);
  EXPECT_NE(r.out.find("checks: 6, failed 6 (exit code 4)"), std::string::npos) << r.out;
}

TEST_F(CliCalibCompare, ThresholdsMustBePositiveAndFinite) {
  WriteJson("in/a.json", CheckCamera(640, 0.5));
  for (const char* bad : {"0", "-1", "inf", "nan"}) {
    EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/a.json", "in/a.json", "--max-px=" + std::string(bad), "--junit", "out/c.xml"}),
                          "calib-compare", kBadInput, "--max-px", {}))
        << bad;
    EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/a.json", "in/a.json", "--max-sigma=" + std::string(bad)}), "calib-compare", kBadInput,
                          "--max-sigma", {}))
        << bad;
  }
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/a.json", "in/a.json", "--max-px", "0"}), "calib-compare", kBadInput,
                        "--max-px: 0 is not a positive number", {"give a bound > 0 in px"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibCompare, MaxSigmaNeedsBothCovariances) {
  WriteJson("in/a.json", CheckCamera(640, 0.5));
  WriteJson("in/truth.json", CheckCamera(640, 0));
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/a.json", "in/truth.json", "--max-sigma", "3", "--junit", "out/c.xml"}),
                        "calib-compare", kBadInput, "in/truth.json: covariance: none; ", {"--max-sigma", "--max-px"}));
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/a.json", "in/a.json", "--junit", "out/c.xml"}), "calib-compare",
                        kBadInput, "--junit: ", {"no check", "--max-px, --max-sigma or --cross-validate"}));
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/a.json", "in/a.json", "--max-px", "1", "--junit", "in/a.json"}),
                        "calib-compare", kBadInput, "in/a.json", {"input"}));
  EXPECT_TRUE(OutDirEmpty());
}

}  // namespace
}  // namespace vstcal::cli_test
