// CLI tests of calib-handeye (issue 22): a recording written as a user's files — the corners as
// correspondences@1 with each view's time, the tracker's log as TUM text (metres) and as poses@1,
// the camera as camera@1 — solved to the truth of tests/support/handeye_scenes.h; every bad input
// with its exit code, one line naming the file and line or field, and nothing written.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <opencv2/core.hpp>
#include <fstream>

#include "cli_fixture.h"
#include "support/handeye_scenes.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/handeye/pose_log_io.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal::cli_test {
namespace {

constexpr std::string_view kTool = "calib-handeye";

class CliCalibHandEye : public CliTest {
 protected:
  // The bootstrap tests' recording: 16 views a quarter of the way between the 100 Hz reports, the
  // tracker's every report with 0.05° and 0.2 mm per axis, 0.2 px on the corners.
  static HandEyeSpec SixteenViewsNoisyTracker() {
    HandEyeSpec spec = testing::HandEyeTestSpec(0.0325, 0.2, 3001);
    spec.tracker_noise_deg = 0.05;
    spec.tracker_noise = 0.2;
    spec.views = 16;
    return spec;
  }

  // in/corners.json, in/poses.txt (TUM, metres), in/poses.json (poses@1, mm), in/camera.json.
  void WriteRecording(const testing::HandEyeRecording& r) const {
    Correspondences c;
    c.image_size = r.camera.image_size;
    c.rig = Rig::kPlanarViews;
    for (const TimedView& v : r.views) c.views.push_back({v.name, "", std::nullopt, v.observations, v.time});
    WriteText("in/corners.json", DumpJson(CorrespondencesToJson(c, Provenance{})));
    CalibratedCamera camera;
    camera.camera = r.camera;
    camera.method = "synthetic";
    WriteText("in/camera.json", DumpJson(CameraToJson(camera, Provenance{}, {})));
    std::string tum = "# timestamp tx ty tz qx qy qz qw (metres)\n";
    for (const TrackedPose& p : r.log) {
      const auto q = QuaternionWxyzFromRotation(p.tracker_from_hmd.R);
      char line[300];
      std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", p.time, p.tracker_from_hmd.t.x() / 1000,
                    p.tracker_from_hmd.t.y() / 1000, p.tracker_from_hmd.t.z() / 1000, q[1], q[2], q[3], q[0]);
      tum += line;
    }
    WriteText("in/poses.txt", tum);
    PoseLog log;
    log.length_unit = LengthUnit::kMillimetre;
    log.poses = r.log;
    WriteText("in/poses.json", DumpJson(PoseLogToJson(log, Provenance{})));
  }
};

TEST_F(CliCalibHandEye, RecoversTheCameraOnTheHeadsetAndTheClockOffset) {
  WriteRecording(testing::RecordHandEye(0.03, 0.2, 5));
  const CommandResult r = Run(kTool, {"solve", "in/corners.json", "--poses", "in/poses.txt", "--camera", "in/camera.json", "-o", "out/he.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.err.find("calib-handeye: 30 views, 1555 corners, 1001 tracker reports"), std::string::npos) << r.err;
  // The offset in milliseconds (30 ms here, known to a few µs): "time offset: 29.99… ms ± 0.0… ms".
  const size_t at = r.err.find("time offset: ");
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_NEAR(std::stod(r.err.substr(at + 13)), 30.0, 0.05) << r.err;
  EXPECT_NE(r.err.find(" ms ± ", at), std::string::npos) << r.err;
  const Json he = ReadJson("out/he.json");
  EXPECT_EQ(he.at("format"), "vstcal/handeye@1");
  EXPECT_EQ(he.at("length_unit"), "mm");
  ASSERT_EQ(he.at("covariance").at("parameters").size(), 15u);
  EXPECT_EQ(he.at("covariance").at("parameters")[12], "time_offset");
  EXPECT_EQ(he.at("covariance").at("parameters")[13], "tracker_noise.rotation");
  EXPECT_EQ(he.at("covariance").at("parameters")[14], "tracker_noise.translation");
  // The tracker is exact here: its noise σ's are bounded far below a real tracker's 0.02° and 0.1 mm.
  EXPECT_LT(he.at("tracker_noise").at("translation").at("ci95")[1].get<double>(), 0.05);
  EXPECT_NEAR(he.at("tracker_noise").at("corner_px").at("sigma").get<double>(), 0.2, 0.01);
  EXPECT_NE(r.err.find("  tracker noise (estimated jointly, 30 instants): rotation "), std::string::npos) << r.err;
  const double offset = he.at("time_offset_s"), sigma = std::sqrt(he.at("covariance").at("matrix")[12][12].get<double>());
  EXPECT_LT(std::abs(offset - 0.03), 4 * sigma);
  EXPECT_LT(sigma, 0.002);
  for (int i = 0; i < 3; ++i) {
    const double t = he.at("hmd_from_camera").at("t")[i], sd = std::sqrt(he.at("covariance").at("matrix")[3 + i][3 + i].get<double>());
    EXPECT_LT(std::abs(t - testing::kHmdFromCamera.t(i)), 1.0) << i << " σ(ρ) " << sd;
  }
  // OpenCV reads the YAML: calibrateHandEye's names, the same numbers.
  ASSERT_EQ(Run(kTool, {"solve", "in/corners.json", "--poses", "in/poses.txt", "--camera", "in/camera.json", "-o", "out/he3.json", "--opencv",
                        "out/he.yaml", "--bootstrap", "0"}).exit_code, kOk);
  cv::FileStorage fs(Path("out/he.yaml").string(), cv::FileStorage::READ);
  cv::Mat t_cam2gripper;
  fs["t_cam2gripper"] >> t_cam2gripper;
  ASSERT_EQ(t_cam2gripper.rows, 3);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(t_cam2gripper.at<double>(i), he.at("hmd_from_camera").at("t")[i].get<double>(), 1e-9);
  EXPECT_NEAR(static_cast<double>(fs["time_offset"]), offset, 1e-12);
  // The same log as poses@1 (mm) gives the same answer.
  ASSERT_EQ(Run(kTool, {"solve", "in/corners.json", "--poses", "in/poses.json", "--camera", "in/camera.json", "--bootstrap", "0", "-o", "out/he2.json"}).exit_code, kOk);
  EXPECT_NEAR(ReadJson("out/he2.json").at("time_offset_s").get<double>(), offset, 1e-9);
  EXPECT_NEAR(ReadJson("out/he2.json").at("hmd_from_camera").at("t")[0].get<double>(), he.at("hmd_from_camera").at("t")[0].get<double>(), 1e-6);
}

// A stereo rig: the left camera's views as CORNERS, the right's with --right, the rig (stereo@1)
// with --rig; both cameras' corners in one solve, the rig named in the file. A right view that pairs
// with no left view, and views of another size than the rig's camera, are refused.
TEST_F(CliCalibHandEye, SolvesAStereoRigAndRefusesUnpairableViews) {
  const testing::HandEyeRigRecording r = testing::RecordHandEyeRig(0.03, 0.2, 9);
  WriteRecording(r.left);
  const auto write_views = [&](const std::string& path, const std::vector<TimedView>& views) {
    Correspondences c;
    c.image_size = r.left.camera.image_size;
    c.rig = Rig::kPlanarViews;
    for (const TimedView& v : views) c.views.push_back({v.name, "", std::nullopt, v.observations, v.time});
    WriteText(path, DumpJson(CorrespondencesToJson(c, Provenance{})));
  };
  write_views("in/right.json", r.rig.views);
  StereoRig rig;
  rig.method = "assembled";
  rig.left.camera = r.left.camera;
  rig.right.camera = r.rig.right;
  rig.left.method = rig.right.method = "synthetic";
  rig.right_from_left = r.rig.right_from_left;
  WriteText("in/rig.json", DumpJson(StereoRigToJson(rig, Provenance{})));
  const CommandResult ok = Run(kTool, {"solve", "in/corners.json", "--right", "in/right.json", "--rig", "in/rig.json", "--poses", "in/poses.txt",
                                       "--bootstrap", "0", "-o", "out/he.json"});
  ASSERT_EQ(ok.exit_code, kOk) << ok.err;
  EXPECT_NE(ok.err.find("calib-handeye: 30 left + 30 right views, 3067 corners"), std::string::npos) << ok.err;
  EXPECT_NE(ok.err.find("rig: in/rig.json (right_from_left held; baseline 64.0062 mm), the right camera's views paired by name"), std::string::npos)
      << ok.err;
  const Json he = ReadJson("out/he.json");
  EXPECT_EQ(he.at("rig").at("file"), "in/rig.json");
  EXPECT_EQ(he.at("rig").at("right_views"), 30);
  EXPECT_EQ(he.at("fit").at("views"), 60);
  EXPECT_NEAR(he.at("rig").at("right_from_left").at("t")[0].get<double>(), -64, 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(he.at("hmd_from_camera").at("t")[i].get<double>(), testing::kHmdFromCamera.t(i), 1.0) << i;
  // The bootstrap simulates the right camera's views through right_from_left too: were they
  // simulated at the left camera's pose, each replicate would be off by the baseline, not by the
  // noise. (4 replicates: a σ good to a factor of a few.)
  const CommandResult boot = Run(kTool, {"solve", "in/corners.json", "--right", "in/right.json", "--rig", "in/rig.json", "--poses", "in/poses.txt",
                                         "--bootstrap", "4", "-o", "out/he_boot.json"});
  ASSERT_EQ(boot.exit_code, kOk) << boot.err;
  const Json he_boot = ReadJson("out/he_boot.json");
  const Json& b = he_boot.at("bootstrap");
  EXPECT_EQ(b.at("solved"), 4);
  for (const int i : {3, 12}) {
    const double first = std::sqrt(he.at("covariance").at("matrix")[i][i].get<double>());
    const double by_bootstrap = std::sqrt(b.at("covariance").at("matrix")[i][i].get<double>());
    EXPECT_GT(by_bootstrap, first / 5) << i;
    EXPECT_LT(by_bootstrap, first * 5) << i;
  }

  // Names that pair with nothing, at times 5 ms off the left views'.
  std::vector<TimedView> unpaired = r.rig.views;
  for (size_t k = 0; k < unpaired.size(); ++k) {
    unpaired[k].name = "shot" + std::to_string(100 + k);
    unpaired[k].time += 0.005;
  }
  write_views("in/unpaired.json", unpaired);
  EXPECT_TRUE(FailsWith(Run(kTool, {"solve", "in/corners.json", "--right", "in/unpaired.json", "--rig", "in/rig.json", "--poses", "in/poses.txt",
                                    "-o", "out/bad.json"}),
                        std::string(kTool), kBadInput, "in/unpaired.json: views[0]: the right camera's view \"shot100\" pairs with no view of in/corners.json",
                        {"by name or by time", "left01, right01"}));
  // The right camera's views of another size than the rig's right camera.
  Json big = ReadJson("in/right.json");
  big["image_size"] = {800, 600};
  WriteJson("in/big.json", big);
  EXPECT_TRUE(FailsWith(Run(kTool, {"solve", "in/corners.json", "--right", "in/big.json", "--rig", "in/rig.json", "--poses", "in/poses.txt",
                                    "-o", "out/bad.json"}),
                        std::string(kTool), kBadInput, "in/big.json: image_size: the views are 800x600 but in/rig.json's right camera is a camera of 640x480",
                        {}));
  // A rig and a camera at once, and a rig without the right camera's views.
  EXPECT_EQ(Run(kTool, {"solve", "in/corners.json", "--right", "in/right.json", "--rig", "in/rig.json", "--camera", "in/camera.json", "--poses",
                        "in/poses.txt", "-o", "out/bad.json"}).exit_code, kBadInput);
  EXPECT_EQ(Run(kTool, {"solve", "in/corners.json", "--rig", "in/rig.json", "--poses", "in/poses.txt", "-o", "out/bad.json"}).exit_code, kBadInput);
  EXPECT_FALSE(fs::exists(Path("out/bad.json")));
}

TEST_F(CliCalibHandEye, RefusesBadLogsAndViews) {
  WriteRecording(testing::RecordHandEye(0.0, 0.0, 6));
  const std::vector<std::string> args = {"solve", "in/corners.json", "--poses", "in/bad.txt", "--camera", "in/camera.json", "-o", "out/he.json"};
  WriteText("in/bad.txt", "0 0 0 0 0 0 0 1\n0.01 0 0 0 0 0 0\n");
  EXPECT_TRUE(FailsWith(Run(kTool, args), std::string(kTool), kBadInput, "in/bad.txt: line 2: ", {"7 numbers where a TUM pose has 8"}));
  WriteText("in/bad.txt", "0 0 0 0 0 0 0 1\n0.01 0 0 0 0 0 0 2\n");
  EXPECT_TRUE(FailsWith(Run(kTool, args), std::string(kTool), kBadInput, "in/bad.txt: line 2: ", {"norm is 2, not 1", "unit quaternions"}));
  WriteText("in/bad.txt", "# log\n1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
  EXPECT_TRUE(FailsWith(Run(kTool, args), std::string(kTool), kBadInput, "in/bad.txt: line 3: ", {"not after the report before it", "sort the log"}));
  WriteText("in/bad.txt", "0 nan 0 0 0 0 0 1\n");
  EXPECT_TRUE(FailsWith(Run(kTool, args), std::string(kTool), kBadInput, "in/bad.txt: line 1: ", {"\"nan\" is not a finite number"}));
  // The log ends before the views do.
  WriteText("in/bad.txt", "0 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
  EXPECT_TRUE(FailsWith(Run(kTool, args), std::string(kTool), kBadInput, "in/corners.json with in/bad.txt: ", {"outside the tracker's log"}));
  // A view without its time.
  Json corners = ReadJson("in/corners.json");
  corners["views"][4].erase("time");
  WriteJson("in/untimed.json", corners);
  EXPECT_TRUE(FailsWith(Run(kTool, {"solve", "in/untimed.json", "--poses", "in/poses.txt", "--camera", "in/camera.json", "-o", "out/he.json"}),
                        std::string(kTool), kBadInput, "in/untimed.json: views[4].time: missing", {"the time its image was taken"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibHandEye, RefusesBadFlags) {
  WriteRecording(testing::RecordHandEye(0.0, 0.0, 8));
  const std::vector<std::string> base = {"solve", "in/corners.json", "--poses", "in/poses.txt", "--camera", "in/camera.json", "-o", "out/he.json"};
  std::vector<std::string> args = base;
  args.insert(args.end(), {"--tum-unit", "furlong"});
  EXPECT_TRUE(FailsWith(Run(kTool, args), std::string(kTool), kBadInput, "--tum-unit: \"furlong\" is not a length unit", {"mm, cm, m or in"}));
  args = base;
  args.insert(args.end(), {"--max-time-offset", "0"});
  EXPECT_TRUE(FailsWith(Run(kTool, args), std::string(kTool), kBadInput, "--max-time-offset: ", {"> 0 and ≤ 10 s"}));
  EXPECT_TRUE(FailsWith(Run(kTool, {"noise", "--poses", "in/poses.txt", "--from", "5", "--to", "5"}), std::string(kTool), kBadInput,
                        "--to: must be after --from", {}));
  EXPECT_TRUE(FailsWith(Run(kTool, {"noise", "--poses", "in/poses.txt", "--from", "0", "--to", "0.02"}), std::string(kTool), kBadInput,
                        "segment: 3 reports", {"at least 10 reports"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibHandEye, RefusesMotionAboutOneAxis) {
  WriteRecording(testing::RecordHandEye(0.0, 0.1, 7, /*one_axis=*/true));
  const CommandResult r = Run(kTool, {"solve", "in/corners.json", "--poses", "in/poses.txt", "--camera", "in/camera.json", "-o", "out/he.json"});
  EXPECT_TRUE(FailsWith(r, std::string(kTool), kDegenerate, "in/corners.json with in/poses.txt: ", {"turned about one axis only", "tilt or roll"}));
  EXPECT_TRUE(OutDirEmpty());
}

// calib-handeye noise on a TUM log whose first 5 s hold the headset still (0.1 mm and 0.02° of
// jitter per axis) before it moves: the σ's with their intervals; a segment into the motion is refused.
TEST_F(CliCalibHandEye, NoiseFromAStaticSegment) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0, 1);
  std::string tum;
  for (int k = 0; k < 2000; ++k) {
    const double t = 0.005 * k, moving = t > 5 ? (t - 5) : 0;
    const Eigen::Vector3d w = Eigen::Vector3d(g(rng), g(rng), g(rng) + 500 * moving) * (0.02 * M_PI / 180);
    const Eigen::Matrix3d R = RotationFromRotvec(w);
    const auto q = QuaternionWxyzFromRotation(R);
    char line[300];
    std::snprintf(line, sizeof line, "%.6f %.9f %.9f %.9f %.12f %.12f %.12f %.12f\n", t, 0.5 + 1e-4 * g(rng), 1e-4 * g(rng), 1.2 + 1e-4 * g(rng),
                  q[1], q[2], q[3], q[0]);
    tum += line;
  }
  WriteText("in/log.txt", tum);
  const CommandResult r = Run(kTool, {"noise", "--poses", "in/log.txt", "--from", "0", "--to", "4.9", "-o", "out/noise.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.err.find("calib-handeye noise: 981 reports from 0.000 to 4.900 s"), std::string::npos) << r.err;
  const Json n = ReadJson("out/noise.json");
  EXPECT_EQ(n.at("format"), "vstcal/tracker-noise@1");
  EXPECT_NEAR(n.at("translation").at("sigma").get<double>(), 0.1, 0.008);  // mm
  EXPECT_NEAR(n.at("rotation_rad").at("sigma").get<double>() * 180 / M_PI, 0.02, 0.0016);
  EXPECT_TRUE(FailsWith(Run(kTool, {"noise", "--poses", "in/log.txt", "--from", "0", "--to", "6", "-o", "out/n2.json"}), std::string(kTool),
                        kDegenerate, "in/log.txt: the headset moved at ", {"held still"}));
  EXPECT_FALSE(fs::exists(Path("out/n2.json")));
}

// The loop a user can run without a headset: calib-synth --rig handeye writes the corners with
// their times, the tracker's TUM log (m), the camera and the truth; calib-handeye solve finds the
// truth within its reported σ's.
TEST_F(CliCalibHandEye, SynthesizedRecordingSolvedToItsTruth) {
  const CommandResult synth = Run("calib-synth", {"--rig", "handeye", "--image-size", "640x480", "--fx", "600", "--grid", "9x6", "--spacing",
                                                  "30", "--noise", "0.2", "--time-offset", "0.04", "-o", "in/rec.json"});
  ASSERT_EQ(synth.exit_code, kOk) << synth.err;
  EXPECT_NE(synth.err.find("calib-synth: a hand-eye recording: 30 timed views"), std::string::npos) << synth.err;
  EXPECT_EQ(List("in"), (std::vector<std::string>{"rec.handeye.truth.json", "rec.json", "rec.poses.txt", "rec.truth.json"}));
  const CommandResult r = Run(kTool, {"solve", "in/rec.json", "--poses", "in/rec.poses.txt", "--camera", "in/rec.truth.json", "-o", "out/he.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json he = ReadJson("out/he.json"), truth = ReadJson("in/rec.handeye.truth.json");
  EXPECT_EQ(truth.at("format"), "vstcal/handeye@1");
  EXPECT_FALSE(truth.contains("covariance"));
  const Json& cov = he.at("covariance").at("matrix");
  EXPECT_LT(std::abs(he.at("time_offset_s").get<double>() - truth.at("time_offset_s").get<double>()), 4 * std::sqrt(cov[12][12].get<double>()));
  for (int i = 0; i < 3; ++i) {
    // ρ's σ bounds t's spread up to the rotation's lever (dt = −[t]× ω + ρ): 1 mm is far beyond both here.
    EXPECT_NEAR(he.at("hmd_from_camera").at("t")[i].get<double>(), truth.at("hmd_from_camera").at("t")[i].get<double>(), 1.0) << i;
  }
  // Flags of one set-up are refused for another.
  EXPECT_TRUE(FailsWith(Run("calib-synth", {"--rig", "planar-views", "--image-size", "640x480", "--fx", "600", "--time-offset", "0.1", "-o", "out/x.json"}),
                        "calib-synth", kBadInput, "--time-offset: applies to --rig handeye only", {}));
  EXPECT_TRUE(OutDirEmpty() || List("out") == std::vector<std::string>{"he.json"});
}

// --view-jitter: 16 evenly spaced views over 10 s, 0.6 s apart, fall at one place between the
// tracker's 100 Hz reports (all 16 times the same modulo 10 ms); with one report interval of jitter
// each moves later by less than 10 ms and they fall at many places. Jitter past the views' spacing
// (0.6 s) is refused, nothing written.
TEST_F(CliCalibHandEye, ViewJitterMovesTheViewsBetweenTheReports) {
  const auto phases = [&](const std::string& file) {
    std::vector<double> out;
    const Json views = ReadJson(file).at("views");
    for (const Json& v : views) out.push_back(std::fmod(v.at("time").get<double>() + 1e-9, 0.01));
    return out;
  };
  const std::vector<std::string> common = {"--rig", "handeye", "--image-size", "640x480", "--fx", "600", "--grid", "9x6", "--spacing", "30", "--views", "16"};
  std::vector<std::string> locked = common, jittered = common;
  locked.insert(locked.end(), {"-o", "in/locked.json"});
  jittered.insert(jittered.end(), {"--view-jitter", "0.01", "-o", "in/jittered.json"});
  ASSERT_EQ(Run("calib-synth", locked).exit_code, kOk);
  ASSERT_EQ(Run("calib-synth", jittered).exit_code, kOk);
  const std::vector<double> a = phases("in/locked.json"), b = phases("in/jittered.json");
  ASSERT_EQ(a.size(), 16u);
  ASSERT_EQ(b.size(), 16u);
  const Json ta = ReadJson("in/locked.json").at("views"), tb = ReadJson("in/jittered.json").at("views");
  double lowest = 1, highest = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i], a[0], 1e-6) << i;
    const double moved = tb[i].at("time").get<double>() - ta[i].at("time").get<double>();
    EXPECT_GE(moved, 0) << i;
    EXPECT_LT(moved, 0.01) << i;
    lowest = std::min(lowest, b[i]);
    highest = std::max(highest, b[i]);
  }
  // 16 uniform draws: the chance that all fall within half of the interval is 16 · 2⁻¹⁵ (and the
  // draws are the seed's, the same on every run).
  EXPECT_GT(highest - lowest, 0.005);
  std::vector<std::string> too_much = common;
  too_much.insert(too_much.end(), {"--view-jitter", "0.7", "-o", "out/x.json"});
  EXPECT_TRUE(FailsWith(Run("calib-synth", too_much), "calib-synth", kBadInput, "--view-jitter: must be at least 0 and less than both the views' spacing", {}));
  EXPECT_TRUE(OutDirEmpty());
}

// A bad frame (one view's corners 3 px off) is dropped by default, named in the summary and in
// rejected_views; --keep-all-views keeps it, and the fit then shows it.
TEST_F(CliCalibHandEye, DropsABadFrameUnlessToldToKeepAll) {
  testing::HandEyeRecording r = testing::RecordHandEye(0.03, 0.2, 5);
  for (Observation& o : r.views[7].observations) o.pixel.x() += 3;
  WriteRecording(r);
  const std::vector<std::string> args = {"solve", "in/corners.json", "--poses", "in/poses.txt", "--camera", "in/camera.json"};
  std::vector<std::string> dropping = args, keeping = args;
  dropping.insert(dropping.end(), {"-o", "out/dropped.json"});
  keeping.insert(keeping.end(), {"--keep-all-views", "--bootstrap", "0", "-o", "out/kept.json"});
  const CommandResult d = Run(kTool, dropping);
  ASSERT_EQ(d.exit_code, kOk) << d.err;
  EXPECT_NE(d.err.find("calib-handeye: 29 views (of 30; bad frames dropped below)"), std::string::npos) << d.err;
  EXPECT_NE(d.err.find("dropped view \"" + r.views[7].name + "\""), std::string::npos) << d.err;
  const Json dropped = ReadJson("out/dropped.json");
  ASSERT_EQ(dropped.at("rejected_views").size(), 1u);
  EXPECT_EQ(dropped["rejected_views"][0]["name"], r.views[7].name);
  EXPECT_EQ(dropped["rejected_views"][0]["view"], 7);
  EXPECT_EQ(dropped.at("fit").at("views"), 29);
  const CommandResult k = Run(kTool, keeping);
  ASSERT_EQ(k.exit_code, kOk) << k.err;
  const Json kept = ReadJson("out/kept.json");
  EXPECT_TRUE(kept.at("rejected_views").empty());
  EXPECT_EQ(kept.at("fit").at("views"), 30);
  EXPECT_GT(kept["fit"]["sigma_px"].get<double>(), 2 * dropped["fit"]["sigma_px"].get<double>());
}

// --bootstrap N (docs/math/handeye.md#delta-bootstrap): a noisy tracker's recording of 16 views,
// solved with 10 replicates — the file's "bootstrap" holds them all solved, δ's σ beside the
// first-order one (the two within a factor 2: they estimate the same spread), the seed in the
// provenance; the same bytes on 2 threads as on 1 (replicate b draws from (seed, b) alone), another
// seed another σ. Without the flag, or with --bootstrap 0, none, the summary saying so. One
// replicate, --seed or --threads without a bootstrap and 300 threads are refused with nothing written.
TEST_F(CliCalibHandEye, BootstrapsTheCovarianceDeterministically) {
  HandEyeSpec spec = SixteenViewsNoisyTracker();
  WriteRecording(testing::RecordHandEye(spec));
  const std::vector<std::string> base = {"solve", "in/corners.json", "--poses", "in/poses.json", "--camera", "in/camera.json"};
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  const CommandResult r = Run(kTool, with({"--bootstrap", "10", "--seed", "7", "-o", "out/b1.json"}));
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.err.find(" ms, σ by the bootstrap (10 of 10 replicates solved; first-order ± "), std::string::npos) << r.err;
  const Json he = ReadJson("out/b1.json");
  ASSERT_TRUE(he.contains("bootstrap"));
  const Json& b = he.at("bootstrap");
  EXPECT_EQ(b.at("replicates"), 10);
  EXPECT_EQ(b.at("solved"), 10);
  EXPECT_EQ(b.at("seed"), 7);
  EXPECT_EQ(he.at("provenance").at("seed"), 7);
  ASSERT_EQ(b.at("covariance").at("parameters").size(), 13u);
  EXPECT_EQ(b.at("covariance").at("parameters")[12], "time_offset");
  const double boot = b.at("time_offset_sigma_s"), first = b.at("first_order_time_offset_sigma_s");
  EXPECT_EQ(first, std::sqrt(he.at("covariance").at("matrix")[12][12].get<double>()));
  EXPECT_EQ(boot, std::sqrt(b.at("covariance").at("matrix")[12][12].get<double>()));
  EXPECT_GT(boot, first / 2);
  EXPECT_LT(boot, first * 2);
  ASSERT_EQ(Run(kTool, with({"--bootstrap", "10", "--seed", "7", "--threads", "2", "-o", "out/b2.json"})).exit_code, kOk);
  EXPECT_EQ(ReadText("out/b2.json").substr(0, ReadText("out/b2.json").find("\"provenance\"")),
            ReadText("out/b1.json").substr(0, ReadText("out/b1.json").find("\"provenance\"")));
  ASSERT_EQ(Run(kTool, with({"--bootstrap", "10", "--seed", "8", "-o", "out/b3.json"})).exit_code, kOk);
  EXPECT_NE(ReadJson("out/b3.json").at("bootstrap").at("time_offset_sigma_s").get<double>(), boot);
  // By default none: the first-order σ, named as such, and no seed in the provenance.
  const CommandResult by_default = Run(kTool, with({"-o", "out/default.json"}));
  ASSERT_EQ(by_default.exit_code, kOk) << by_default.err;
  EXPECT_NE(by_default.err.find(" ms, σ first-order (--bootstrap B also runs the bootstrap)"), std::string::npos) << by_default.err;
  const Json he_default = ReadJson("out/default.json");
  EXPECT_FALSE(he_default.contains("bootstrap"));
  EXPECT_TRUE(he_default.at("provenance").at("seed").is_null());
  EXPECT_EQ(he_default.at("time_offset_s"), he.at("time_offset_s"));
  const CommandResult none = Run(kTool, with({"--bootstrap", "0", "-o", "out/none.json"}));
  ASSERT_EQ(none.exit_code, kOk) << none.err;
  EXPECT_NE(none.err.find(" ms, σ first-order (--bootstrap B also runs the bootstrap)"), std::string::npos) << none.err;
  EXPECT_FALSE(ReadJson("out/none.json").contains("bootstrap"));
  EXPECT_TRUE(ReadJson("out/none.json").at("provenance").at("seed").is_null());  // no bootstrap, no random draw
  EXPECT_EQ(ReadJson("out/none.json").at("time_offset_s"), he.at("time_offset_s"));
  fs::remove_all(Path("out"));
  fs::create_directories(Path("out"));
  EXPECT_TRUE(FailsWith(Run(kTool, with({"--bootstrap", "1", "-o", "out/x.json"})), std::string(kTool), kBadInput, "--bootstrap: 1 replicates",
                        {"give 2 … 100000"}));
  EXPECT_TRUE(FailsWith(Run(kTool, with({"--bootstrap", "10", "--threads", "300", "-o", "out/x.json"})), std::string(kTool), kBadInput,
                        "--threads: 300", {"0 (all cores) … 256"}));
  EXPECT_TRUE(FailsWith(Run(kTool, with({"--bootstrap", "0", "--seed", "3", "-o", "out/x.json"})), std::string(kTool), kBadInput, "--seed",
                        {"which runs only with --bootstrap B"}));
  EXPECT_TRUE(FailsWith(Run(kTool, with({"--seed", "3", "-o", "out/x.json"})), std::string(kTool), kBadInput, "--seed",
                        {"which runs only with --bootstrap B"}));
  EXPECT_TRUE(FailsWith(Run(kTool, with({"--bootstrap", "0", "--threads", "2", "-o", "out/x.json"})), std::string(kTool), kBadInput,
                        "--threads", {"which runs only with --bootstrap B"}));
  EXPECT_TRUE(OutDirEmpty());
}

// Where the views fall between the tracker's reports (docs/math/handeye.md#report-phases) is
// reported, not acted on: the recording above, 16 views a quarter of the way between two reports,
// says where its views sit and is not bootstrapped; the same recording with a report interval of
// jitter on the camera's clock says they fall at many places. Both files hold the phases.
TEST_F(CliCalibHandEye, SaysWhereTheViewsFallBetweenTheReports) {
  HandEyeSpec spec = SixteenViewsNoisyTracker();
  WriteRecording(testing::RecordHandEye(spec));
  const std::vector<std::string> solve = {"solve", "in/corners.json", "--poses", "in/poses.json", "--camera", "in/camera.json", "-o", "out/locked.json"};
  const CommandResult locked = Run(kTool, solve);
  ASSERT_EQ(locked.exit_code, kOk) << locked.err;
  EXPECT_NE(locked.err.find(" ms, σ first-order (--bootstrap B also runs the bootstrap)"), std::string::npos) << locked.err;
  EXPECT_NE(locked.err.find("the views sit at one place between the tracker's reports, "), std::string::npos) << locked.err;
  const Json locked_file = ReadJson("out/locked.json");
  EXPECT_FALSE(locked_file.contains("bootstrap"));
  const Json phases = locked_file.at("fit").at("report_phases");
  EXPECT_GT(phases.at("concentration").get<double>(), 0.99);
  // The views at 0.5 + 0.6 k s and the reports every 10 ms from 0: at the solved δ̂ every view sits
  // frac(δ̂ / 10 ms) of the way.
  const double place = std::fmod(locked_file.at("time_offset_s").get<double>() / 0.01, 1.0);
  EXPECT_NEAR(std::remainder(phases.at("mean").get<double>() - place, 1.0), 0.0, 1e-6);
  EXPECT_EQ(phases.at("instants"), 16);

  spec.view_jitter = 0.01;
  WriteRecording(testing::RecordHandEye(spec));
  std::vector<std::string> spread_args = solve;
  spread_args.back() = "out/spread.json";
  const CommandResult spread = Run(kTool, spread_args);
  ASSERT_EQ(spread.exit_code, kOk) << spread.err;
  EXPECT_NE(spread.err.find("the views fall at many places between the tracker's reports (concentration 0."), std::string::npos) << spread.err;
  const Json he = ReadJson("out/spread.json");
  EXPECT_FALSE(he.contains("bootstrap"));
  EXPECT_TRUE(he.at("provenance").at("seed").is_null());
  EXPECT_LT(he.at("fit").at("report_phases").at("concentration").get<double>(), 0.5);
}

// Issue 22 item 5, from photographs: calib-synth renders the recording's views (the chessboard its
// grid is), calib-capture detect finds the corners and gives each image its time from times.txt,
// calib-handeye solves — X, Z and the offset to the truth within their own covariance.
TEST_F(CliCalibHandEye, FromRenderedPhotographsThroughDetection) {
  const CommandResult synth = Run("calib-synth", {"--rig", "handeye", "--image-size", "640x480", "--fx", "600", "--grid", "9x6", "--spacing",
                                                  "30", "--distance", "800", "--views", "10", "--images", "in/images", "-o", "in/rec.json"});
  ASSERT_EQ(synth.exit_code, kOk) << synth.err;
  EXPECT_EQ(List("in/images").size(), 12u);  // 10 views, board.target.json, times.txt
  const CommandResult detect = Run("calib-capture", {"detect", "in/images/board.target.json", "in/images", "--times", "in/images/times.txt",
                                                     "-o", "in/corners.json"});
  ASSERT_EQ(detect.exit_code, kOk) << detect.err;
  const Json corners = ReadJson("in/corners.json"), rec = ReadJson("in/rec.json");
  ASSERT_GE(corners.at("views").size(), 8u) << detect.err;
  // Each found view's time is its image's, as calib-synth gave it (views frame-k ↔ view-0k.png).
  for (const Json& v : corners.at("views")) {
    const int k = std::stoi(v.at("name").get<std::string>().substr(5));
    EXPECT_EQ(v.at("time").get<double>(), rec.at("views")[static_cast<size_t>(k)].at("time").get<double>()) << k;
  }
  const CommandResult r = Run(kTool, {"solve", "in/corners.json", "--poses", "in/rec.poses.txt", "--camera", "in/rec.truth.json", "-o", "out/he.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json he = ReadJson("out/he.json"), truth = ReadJson("in/rec.handeye.truth.json");
  const Json& cov = he.at("covariance").at("matrix");
  EXPECT_LT(std::abs(he.at("time_offset_s").get<double>() - truth.at("time_offset_s").get<double>()), 4 * std::sqrt(cov[12][12].get<double>()));
  EXPECT_LT(std::sqrt(cov[12][12].get<double>()), 1e-4);  // corners good to a few hundredths of a pixel: δ to well under 0.1 ms
  for (const char* pose : {"hmd_from_camera", "tracker_from_board"}) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(he.at(pose).at("t")[i].get<double>(), truth.at(pose).at("t")[i].get<double>(), 0.1) << pose << i;
  }
}

}  // namespace
}  // namespace vstcal::cli_test
