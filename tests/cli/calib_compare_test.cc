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
