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

}  // namespace
}  // namespace vstcal::cli_test
