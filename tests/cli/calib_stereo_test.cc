// CLI tests of calib-stereo: rigs solved from both cameras' views (planar views and a volume), rigs
// assembled from two cameras and exported to OpenCV and mrcal, binocular registration of tracked
// sequences, display planning; every bad input gives its documented exit code, one line naming the
// file, the field and the fix, and no output file.
#include <sstream>
#include <Eigen/Cholesky>
#include <opencv2/imgcodecs.hpp>

#include "cli_fixture.h"
#include "support/scenes.h"
#include "support/stereo_rigs.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/formats/stereo/stereo_io.h"

namespace vstcal::cli_test {
namespace {

constexpr std::string_view kTool = "calib-stereo";

class CliCalibStereo : public CliTest {
 protected:
  // in/left.json and in/right.json: the ZED-like rig's cameras (camera@1, no pose), and in/rig.json.
  void WriteInputs() {
    const StereoRig rig = testing::ZedLikeRig();
    const Provenance p{"test", {}, std::nullopt};
    WriteText("in/left.json", DumpJson(CameraToJson(rig.left, p)));
    WriteText("in/right.json", DumpJson(CameraToJson(rig.right, p)));
    WriteText("in/rig.json", DumpJson(StereoRigToJson(rig, p)));
  }

  CommandResult Ok(const std::vector<std::string>& args) {
    const CommandResult r = Run(kTool, args);
    EXPECT_EQ(r.exit_code, kOk) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    return r;
  }

  // The rig with one field replaced (a JSON pointer such as "/baseline"), written to in/bad.json.
  void WriteBadRig(const std::string& pointer, const Json& value) {
    Json rig = ReadJson("in/rig.json");
    rig[Json::json_pointer(pointer)] = value;
    WriteJson("in/bad.json", rig);
  }

  // The error contract, and nothing new in out/ (no output, no stray temporary).
  ::testing::AssertionResult Fails(const std::vector<std::string>& args, int code, const std::string& location,
                                   const std::vector<std::string>& phrases) {
    const std::vector<std::string> before = List("out");
    const CommandResult r = Run(kTool, args);
    auto result = FailsWith(r, kTool, code, location, phrases);
    if (!result) return result;
    if (List("out") != before) return ::testing::AssertionFailure() << "the failing run left a file in out/";
    return ::testing::AssertionSuccess();
  }

  // Both cameras' views (in/l.json and in/r.json unless named) with 0.2 px of noise.
  void WriteStereoViews(testing::StereoViews views, const std::string& left = "in/l.json",
                        const std::string& right = "in/r.json") {
    const Provenance p{"test", {}, std::nullopt};
    views.left = testing::WithNoise(views.left, 0.2, 1);
    views.right = testing::WithNoise(views.right, 0.2, 2);
    WriteText(left, DumpJson(CorrespondencesToJson(views.left, p)));
    WriteText(right, DumpJson(CorrespondencesToJson(views.right, p)));
  }
};

Eigen::Vector3d Vec(const Json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

TEST_F(CliCalibStereo, AssembleThenExportThroughMrcalComesBack) {
  WriteInputs();
  Ok({"assemble", "in/left.json", "in/right.json", "--translation", "-63,0.2,-0.4", "--rotvec-deg",
      "0.11459155902616464,-0.22918311805232929,0.057295779513082323", "-o", "out/rig.json"});
  const Json rig = ReadJson("out/rig.json");
  EXPECT_EQ(rig["format"], "vstcal/stereo@1");
  EXPECT_EQ(rig["method"], "assembled");
  EXPECT_NEAR(rig["baseline"].get<double>(), std::sqrt(63.0 * 63 + 0.04 + 0.16), 1e-12);
  EXPECT_TRUE(rig["fit"].is_null());
  EXPECT_EQ(rig["provenance"]["tool"], "calib-stereo");
  // Two mrcal files sharing the left camera's frame, assembled again without --translation.
  Ok({"export", "out/rig.json", "--mrcal", "out/l.cameramodel", "out/r.cameramodel", "--opencv", "out/stereo.yaml"});
  Ok({"assemble", "out/l.cameramodel", "out/r.cameramodel", "-o", "out/back.json"});
  const Json back = ReadJson("out/back.json");
  EXPECT_EQ(back["right_from_left"]["t"], rig["right_from_left"]["t"]);
  EXPECT_LT((Vec(back["right_from_left"]["R"][0]) - Vec(rig["right_from_left"]["R"][0])).norm(), 1e-15);
  EXPECT_EQ(back["left"]["K"], rig["left"]["K"]);
  EXPECT_EQ(back["right"]["distortion"], rig["right"]["distortion"]);
  EXPECT_NE(ReadText("out/stereo.yaml").find("F: !!opencv-matrix"), std::string::npos);
}

TEST_F(CliCalibStereo, AssembleFromTwoCamerasSolvedInOneWorld) {
  WriteInputs();
  StereoRig rig = testing::ZedLikeRig();
  CalibratedCamera left = rig.left, right = rig.right;
  left.camera_from_world = Rigid3d::FromRotvec(Eigen::Vector3d(0.1, 0.2, -0.1), Eigen::Vector3d(10, 20, 1500));
  right.camera_from_world = rig.right_from_left * *left.camera_from_world;
  const Provenance p{"test", {}, std::nullopt};
  WriteText("in/left-posed.json", DumpJson(CameraToJson(left, p)));
  WriteText("in/right-posed.json", DumpJson(CameraToJson(right, p)));
  Ok({"assemble", "in/left-posed.json", "in/right-posed.json", "--rectify", "--alpha", "0", "-o", "out/rig.json"});
  const StereoRig back = ReadStereoRig(Path("out/rig.json"));
  EXPECT_LT((back.right_from_left.t - rig.right_from_left.t).norm(), 1e-9);
  ASSERT_TRUE(back.rectification.has_value());
  EXPECT_EQ(back.rectification->alpha, 0.0);
  // A camera in metres cannot be composed with one in millimetres.
  right.length_unit = LengthUnit::kMetre;
  WriteText("in/right-m.json", DumpJson(CameraToJson(right, p)));
  EXPECT_TRUE(Fails({"assemble", "in/left-posed.json", "in/right-m.json", "-o", "out/rig.json"}, kBadInput,
                    "in/right-m.json: length_unit: \"m\", but in/left-posed.json is in \"mm\"", {"one length unit"}));
}

TEST_F(CliCalibStereo, AssembleRefusesBadInput) {
  WriteInputs();
  const std::vector<std::string> base = {"assemble", "in/left.json", "in/right.json", "-o", "out/rig.json"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  EXPECT_TRUE(Fails(base, kBadInput, "in/left.json: camera_from_world: absent", {"give right_from_left"}));
  EXPECT_TRUE(Fails(with({"--rotvec-deg", "0,0,0"}), kBadInput, "--rotvec-deg: given without --translation", {}));
  EXPECT_TRUE(Fails(with({"--translation", "0,0,0"}), kBadInput, "right_from_left: the two cameras coincide", {}));
  EXPECT_TRUE(Fails(with({"--translation", "-63,0"}), kBadInput, "--translation", {}));
  EXPECT_TRUE(Fails(with({"--translation", "-63,0,nan"}), kBadInput, "--translation", {"finite"}));
  EXPECT_TRUE(Fails(with({"--translation", "-63,0,0", "--alpha", "0.5"}), kBadInput, "--alpha: applies with --rectify only", {}));
  // stereoRectify takes one image size.
  CalibratedCamera right = testing::ZedLikeRig().right;
  right.camera.image_size = {1920, 1080};
  WriteText("in/right-hd.json", DumpJson(CameraToJson(right, {"test", {}, std::nullopt})));
  EXPECT_TRUE(Fails({"assemble", "in/left.json", "in/right-hd.json", "--translation", "-63,0,0", "--rectify", "-o", "out/rig.json"},
                    kBadInput, "out/rig.json: right.image_size: 1920×1080, but the left camera's is 1280×720", {"one image size"}));
  WriteText("in/cam.txt", "");
  EXPECT_TRUE(Fails({"assemble", "in/cam.txt", "in/right.json", "--translation", "-63,0,0", "-o", "out/rig.json"}, kBadInput,
                    "in/cam.txt: cannot tell the format from the file name", {}));
}

TEST_F(CliCalibStereo, RigReaderNamesTheFieldAndTheFix) {
  WriteInputs();
  const std::vector<std::string> args = {"export", "in/bad.json", "--opencv", "out/s.yaml"};
  WriteBadRig("/baseline", 64.0);
  EXPECT_TRUE(Fails(args, kBadInput, "in/bad.json: baseline: disagrees with |right_from_left.t|", {"distance between the camera centres"}));
  WriteBadRig("/left/camera_from_world", Json{{"R", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, {"t", {0, 0, 0}}});
  EXPECT_TRUE(Fails(args, kBadInput, "in/bad.json: left.camera_from_world: a rig's cameras hold intrinsics only", {}));
  WriteBadRig("/right/length_unit", "m");
  EXPECT_TRUE(Fails(args, kBadInput, "in/bad.json: right.length_unit: \"m\", but the rig is in \"mm\"", {}));
  WriteBadRig("/right/K/1/1", -5.0);
  EXPECT_TRUE(Fails(args, kBadInput, "in/bad.json: right.K: fx and fy must be positive", {}));
  WriteBadRig("/right_from_left/t", {0, 0, 0});
  EXPECT_TRUE(Fails(args, kBadInput, "in/bad.json: right_from_left.t: the two cameras coincide (baseline 0)", {}));
  WriteBadRig("/format", "vstcal/camera@1");
  EXPECT_TRUE(Fails(args, kBadInput, "in/bad.json: format: this is a \"vstcal/camera@1\" file, expected \"vstcal/stereo@1\"", {}));
  WriteBadRig("/covariance", Json{{"parameters", {"right_from_left.rx"}}, {"matrix", {{1.0}}}});
  EXPECT_TRUE(Fails(args, kBadInput, "in/bad.json: covariance.parameters: expected 6 items, got 1", {}));
  WriteBadRig("/right_from_left/R/0/0", 0.9);
  EXPECT_TRUE(Fails(args, kBadInput, "in/bad.json: right_from_left.R: not a rotation matrix", {}));
  EXPECT_TRUE(Fails({"export", "in/none.json", "--opencv", "out/s.yaml"}, kBadInput, "in/none.json", {}));
}

TEST_F(CliCalibStereo, ExportRefusesConflictingOutputs) {
  WriteInputs();
  EXPECT_TRUE(Fails({"export", "in/rig.json"}, kBadInput, "export: nothing to write", {}));
  EXPECT_TRUE(Fails({"export", "in/rig.json", "--mrcal", "out/a.cameramodel", "out/a.cameramodel"}, kBadInput,
                    "the same file is given for two outputs", {}));
  EXPECT_TRUE(Fails({"export", "in/rig.json", "--mrcal", "out/l.cameramodel", "out/r.cameramodel", "--rectify"}, kBadInput,
                    "--rectify: the rectification goes into --opencv's YAML", {}));
}

// An output naming an input (directly or by another path to it) is refused; the input is unchanged.
TEST_F(CliCalibStereo, NeverOverwritesAnInput) {
  WriteInputs();
  Ok({"simulate", "in/rig.json", "-o", "out/tracks.json", "--frames", "3", "--seed", "1"});
  const std::string rig = ReadText("in/rig.json"), tracks = ReadText("out/tracks.json");
  EXPECT_TRUE(Fails({"register", "in/rig.json", "out/tracks.json", "-o", "out/../out/tracks.json"}, kBadInput,
                    "out/../out/tracks.json: is the input out/tracks.json", {"never overwrites its inputs"}));
  EXPECT_TRUE(Fails({"export", "in/rig.json", "--opencv", "in/rig.json"}, kBadInput, "in/rig.json: is the input", {"never overwrites its inputs"}));
  EXPECT_TRUE(Fails({"assemble", "in/left.json", "in/right.json", "--translation", "-63,0,0", "-o", "in/right.json"},
                    kBadInput, "in/right.json: is the input", {"never overwrites its inputs"}));
  EXPECT_EQ(ReadText("in/rig.json"), rig);
  EXPECT_EQ(ReadText("out/tracks.json"), tracks);
}

TEST_F(CliCalibStereo, SimulateThenRegisterReportsAccuracy) {
  WriteInputs();
  Ok({"simulate", "in/rig.json", "-o", "out/tracks.json", "--frames", "20", "--noise", "0.3", "--seed", "4"});
  for (const std::string mode : {"left", "per-eye", "joint"}) {
    const CommandResult r = Ok({"register", "in/rig.json", "out/tracks.json", "--mode", mode, "-o", "out/reg-" + mode + ".json"});
    EXPECT_NE(r.err.find(mode + " registration: 20 of 20 frames registered"), std::string::npos) << r.err;
    const Json reg = ReadJson("out/reg-" + mode + ".json");
    EXPECT_EQ(reg["format"], "vstcal/registration@1");
    EXPECT_EQ(reg["summary"]["registered"], 20);
    EXPECT_EQ(reg["frames"][0]["virtual"]["right"].size(), 8u);
    // 0.3 px noise on four coplanar points 1 m away leaves the tilt uncertain by a degree or so:
    // virtual points up to 40 cm off the plane move by a few pixels (docs/experiments).
    const double rms = reg["summary"]["accuracy"]["right"]["virtual_px"]["rms"].get<double>();
    EXPECT_GT(rms, 0.1) << mode;
    EXPECT_LT(rms, 10.0) << mode;
  }
  // Same input, same bytes (no time stamps, no thread dependence).
  Ok({"register", "in/rig.json", "out/tracks.json", "-o", "out/again.json", "--mode", "left"});
  EXPECT_EQ(ReadJson("out/again.json")["frames"], ReadJson("out/reg-left.json")["frames"]);
}

TEST_F(CliCalibStereo, FramesThatCannotBeRegisteredAreExcludedAndNamed) {
  WriteInputs();
  Ok({"simulate", "in/rig.json", "-o", "in/tracks.json", "--frames", "3", "--noise", "0"});
  Json tracks = ReadJson("in/tracks.json");
  tracks["frames"][1]["left"][2] = nullptr;  // lost by the tracker: 3 points left
  WriteJson("in/lost.json", tracks);
  const CommandResult r = Ok({"register", "in/rig.json", "in/lost.json", "-o", "out/reg.json"});
  EXPECT_NE(r.err.find("excluded frame-1: left eye: fewer than 4 points"), std::string::npos) << r.err;
  const Json reg = ReadJson("out/reg.json");
  EXPECT_EQ(reg["frames"][1]["status"], "excluded");
  EXPECT_EQ(reg["summary"]["excluded"], Json::array({"frame-1"}));
  // Joint registration uses the right eye's four points instead.
  Ok({"register", "in/rig.json", "in/lost.json", "--mode", "joint", "-o", "out/joint.json"});
  EXPECT_EQ(ReadJson("out/joint.json")["summary"]["registered"], 3);
  // No frame at all: degenerate data.
  for (auto& f : tracks["frames"]) f["left"][0] = nullptr;
  WriteJson("in/none.json", tracks);
  EXPECT_TRUE(Fails({"register", "in/rig.json", "in/none.json", "-o", "out/reg2.json"}, kDegenerate,
                    "in/none.json: frames: no frame could be registered", {"fewer than 4 points"}));
}

TEST_F(CliCalibStereo, RegisterRefusesBadTracks) {
  WriteInputs();
  Ok({"simulate", "in/rig.json", "-o", "in/tracks.json", "--frames", "2", "--noise", "0"});
  const Json good = ReadJson("in/tracks.json");
  auto fails_with = [&](const std::string& pointer, const Json& value, int code, const std::string& location) {
    Json t = good;
    t[Json::json_pointer(pointer)] = value;
    WriteJson("in/bad.json", t);
    return Fails({"register", "in/rig.json", "in/bad.json", "-o", "out/reg.json"}, code, location, {});
  };
  EXPECT_TRUE(fails_with("/length_unit", "m", kBadInput, "in/bad.json: length_unit: \"m\", but in/rig.json is in \"mm\""));
  EXPECT_TRUE(fails_with("/image_size/left", {1920, 1080}, kBadInput,
                         "in/bad.json: image_size.left: 1920×1080, but the rig's left camera in in/rig.json is 1280×720"));
  EXPECT_TRUE(fails_with("/image_size/left", {64, 48}, kBadInput, "in/bad.json: frames[0].left[0]: pixel"));
  EXPECT_TRUE(fails_with("/image_size/right", {1920, 1080}, kBadInput,
                         "in/bad.json: image_size.right: 1920×1080, but the rig's right camera in in/rig.json is 1280×720"));
  EXPECT_TRUE(fails_with("/frames/0/left/0", {5000, 10}, kBadInput, "in/bad.json: frames[0].left[0]: pixel (5000, 10) lies outside"));
  EXPECT_TRUE(fails_with("/frames/1/right", Json::array({{1, 2}}), kBadInput, "in/bad.json: frames[1].right: has 1 entries for 4 embedded points"));
  EXPECT_TRUE(fails_with("/frames/1/name", "frame-0", kBadInput, "in/bad.json: frames[1].name: duplicate frame name \"frame-0\""));
  Json three = good;
  three["embedded_points"].erase(3);
  for (auto& f : three["frames"]) f["left"].erase(3), f["right"].erase(3);
  WriteJson("in/bad.json", three);
  EXPECT_TRUE(Fails({"register", "in/rig.json", "in/bad.json", "-o", "out/reg.json"}, kBadInput,
                    "in/bad.json: embedded_points: 3 points; a camera's pose needs at least 4", {}));
  Json line = good;
  for (int i = 0; i < 4; ++i) line["embedded_points"][i]["world"] = {10.0 * i, 0.0, 0.0};
  WriteJson("in/bad.json", line);
  EXPECT_TRUE(Fails({"register", "in/rig.json", "in/bad.json", "-o", "out/reg.json"}, kDegenerate,
                    "in/bad.json: embedded_points: the points lie on one line", {}));
  Json left_only = good;
  for (auto& f : left_only["frames"]) f.erase("right");
  WriteJson("in/bad.json", left_only);
  EXPECT_TRUE(Fails({"register", "in/rig.json", "in/bad.json", "--mode", "per-eye", "-o", "out/reg.json"}, kBadInput,
                    "in/bad.json: frames[0].right: missing; per-eye registration needs", {}));
}

TEST_F(CliCalibStereo, PlanTabulatesSeed000sEquations) {
  Ok({"plan", "--baseline", "63", "--focal-px", "700", "--display-width", "1200", "--z0", "1000", "--depths",
      "500,1000,2000", "--viewer", "screen", "--ipd", "63", "--screen-width", "1028.5714285714287", "--viewing-distance",
      "600", "-o", "out/plan.json"});
  const Json plan = ReadJson("out/plan.json");
  EXPECT_EQ(plan["format"], "vstcal/stereo-plan@1");
  EXPECT_DOUBLE_EQ(plan["translation_px"].get<double>(), 44.1);
  EXPECT_DOUBLE_EQ(plan["depths"][0]["disparity_px"].get<double>(), 88.2);
  EXPECT_EQ(plan["depths"][0]["side"], "front");
  EXPECT_EQ(plan["depths"][1]["side"], "screen");
  EXPECT_EQ(plan["depths"][1]["perceived_depth"].get<double>(), 600.0);  // on the screen
  EXPECT_EQ(plan["behind_screen"]["from"], 1000.0);
  WriteInputs();
  Ok({"plan", "--rig", "in/rig.json", "--display-width", "1200", "--viewer", "hmd", "--ipd", "70", "--depths", "1000", "-o",
      "out/hmd.json"});
  EXPECT_NEAR(ReadJson("out/hmd.json")["depths"][0]["perceived_ratio"].get<double>(), 70 / testing::ZedLikeRig().baseline(), 1e-12);
}

TEST_F(CliCalibStereo, PlanRefusesBadFlags) {
  const std::vector<std::string> base = {"plan", "--display-width", "1200", "-o", "out/plan.json"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  EXPECT_TRUE(Fails(with({"--focal-px", "700"}), kBadInput, "--baseline: required without --rig", {}));
  EXPECT_TRUE(Fails(with({"--baseline", "63"}), kBadInput, "--focal-px, --hfov-deg: give exactly one", {}));
  EXPECT_TRUE(Fails(with({"--baseline", "63", "--hfov-deg", "90", "--z0", "30"}), kBadInput, "--z0: 30 is not beyond 31.5", {}));
  EXPECT_TRUE(Fails(with({"--baseline", "63", "--focal-px", "700", "--viewer", "screen", "--ipd", "63"}), kBadInput,
                    "--screen-width, --viewing-distance: both required", {}));
  EXPECT_TRUE(Fails(with({"--baseline", "63", "--focal-px", "700", "--ipd", "63"}), kBadInput, "--ipd: applies with --viewer", {}));
  EXPECT_TRUE(Fails(with({"--baseline", "-63", "--focal-px", "700"}), kBadInput, "--baseline", {"positive"}));
  EXPECT_TRUE(Fails(with({"--rig", "in/rig.json", "--baseline", "63"}), kBadInput, "--rig: the rig gives the baseline", {}));
}

StereoRig SolvableRig() {
  StereoRig rig = testing::ZedLikeRig();
  rig.left.camera.params.back() = rig.right.camera.params.back() = 0;  // k3: solve estimates k1, k2, p1, p2
  return rig;
}

TEST_F(CliCalibStereo, SolveWritesTheRigWithItsCovarianceAndFit) {
  const StereoRig truth = SolvableRig();
  WriteStereoViews(testing::SyntheticStereoViews(truth, 8, 11));
  const CommandResult r = Ok({"solve", "in/l.json", "in/r.json", "--rectify", "-o", "out/rig.json"});
  EXPECT_NE(r.err.find("8 views seen by both cameras"), std::string::npos) << r.err;
  const StereoRig rig = ReadStereoRig(Path("out/rig.json"));
  EXPECT_EQ(rig.method, "stereo-solve");
  ASSERT_TRUE(rig.covariance);
  ASSERT_TRUE(rig.fit);
  EXPECT_EQ(rig.fit->views.size(), 8u);
  EXPECT_TRUE(rig.rectification);
  const double sigma = *BaselineSigma(rig);
  EXPECT_GT(sigma, 0);
  EXPECT_LT(std::abs(rig.baseline() - truth.baseline()), 5 * sigma) << "σ " << sigma;
  // The solved rig exports like any other; what the formats cannot hold is said once per field,
  // with the tool's name (issue 24: twice, once per mrcal file, without it).
  const CommandResult e = Ok({"export", "out/rig.json", "--opencv", "out/rig.yaml", "--mrcal", "out/l.cameramodel", "out/r.cameramodel"});
  const std::string covariance = "calib-stereo: note: out/rig.json: covariance: not written: the format has no field for it\n";
  const std::string fit = "calib-stereo: note: out/rig.json: fit: not written: the format has no field for it\n";
  EXPECT_EQ(e.err.rfind(covariance), e.err.find(covariance)) << e.err;
  EXPECT_NE(e.err.find(covariance), std::string::npos) << e.err;
  EXPECT_EQ(e.err.rfind(fit), e.err.find(fit)) << e.err;
  EXPECT_NE(e.err.find(fit), std::string::npos) << e.err;
  EXPECT_EQ(e.err.find("\nnote: "), std::string::npos) << e.err;
}

// Fisheye cameras: given as --left-camera/--right-camera ("kannala-brandt") with neither --lens-model
// nor --distortion, their model chooses the lens model and its terms k1…k4 (said in a note), as
// --lens-model kannala-brandt does; cameras of two different families are refused in one line.
TEST_F(CliCalibStereo, FisheyeCamerasChooseTheLensModel) {
  StereoRig truth = testing::ZedLikeRig(false);
  const double kl[4] = {0.021, -0.0043, 0.0011, -0.00017}, kr[4] = {0.019, -0.0039, 0.0009, -0.00015};
  truth.left.camera = Camera::FromK(truth.left.camera.K(), {1280, 720}, KannalaBrandtModel{}, kl);
  truth.right.camera = Camera::FromK(truth.right.camera.K(), {1280, 720}, KannalaBrandtModel{}, kr);
  WriteStereoViews(testing::SyntheticStereoViews(truth, 10, 11));
  const Provenance p{"test", {}, std::nullopt};
  WriteText("in/left.json", DumpJson(CameraToJson(truth.left, p)));
  WriteText("in/right.json", DumpJson(CameraToJson(truth.right, p)));

  const CommandResult r = Ok({"solve", "in/l.json", "in/r.json", "--left-camera", "in/left.json", "--right-camera",
                              "in/right.json", "-o", "out/rig.json"});
  EXPECT_NE(r.err.find("note: lens model \"kannala-brandt\" (terms k1,k2,k3,k4) from in/left.json, as neither "
                       "--lens-model nor --distortion was given"),
            std::string::npos)
      << r.err;
  const StereoRig rig = ReadStereoRig(Path("out/rig.json"));
  for (const CalibratedCamera* c : {&rig.left, &rig.right}) {
    EXPECT_TRUE(std::holds_alternative<KannalaBrandtModel>(c->camera.model)) << c->name;
  }
  ASSERT_TRUE(rig.covariance);
  const double sigma = *BaselineSigma(rig);
  EXPECT_LT(std::abs(rig.baseline() - truth.baseline()), 5 * sigma) << "σ " << sigma;
  // The same rig from the flag, without the cameras' start.
  Ok({"solve", "in/l.json", "in/r.json", "--lens-model", "kannala-brandt", "-o", "out/rig-flag.json"});
  const StereoRig flagged = ReadStereoRig(Path("out/rig-flag.json"));
  EXPECT_TRUE(std::holds_alternative<KannalaBrandtModel>(flagged.left.camera.model));
  EXPECT_LT(std::abs(flagged.baseline() - rig.baseline()), 0.1 * sigma);

  StereoRig mixed = testing::ZedLikeRig();
  WriteText("in/brown.json", DumpJson(CameraToJson(mixed.right, p)));
  WriteText("in/other.json", DumpJson(CameraToJson(truth.left, p)));
  EXPECT_TRUE(Fails({"solve", "in/l.json", "in/r.json", "--left-camera", "in/other.json", "--right-camera", "in/brown.json",
                     "-o", "out/rig2.json"},
                    kBadInput, "in/brown.json: ",
                    {"lens model \"radial-tangential\", but in/other.json is \"kannala-brandt\"", "--lens-model"}));
}

// The summary shows both cameras' lens parameters ± σ and right_from_left's σ, each equal to the
// square root of the written covariance's diagonal.
TEST_F(CliCalibStereo, SolveSummaryShowsEachEstimateWithItsSigma) {
  WriteStereoViews(testing::SyntheticStereoViews(SolvableRig(), 8, 11));
  const CommandResult r = Ok({"solve", "in/l.json", "in/r.json", "-o", "out/rig.json"});
  const StereoRig rig = ReadStereoRig(Path("out/rig.json"));
  const size_t right = r.err.find("right camera:\n");
  ASSERT_NE(r.err.find("left camera:\n"), std::string::npos) << r.err;
  ASSERT_NE(right, std::string::npos) << r.err;
  for (const auto& [camera, from] : {std::pair{&rig.right, right}, std::pair{&rig.left, size_t{0}}}) {
    ASSERT_TRUE(camera->covariance);
    const size_t line = r.err.find("\n  fx ", from);
    ASSERT_NE(line, std::string::npos) << r.err;
    std::istringstream words(r.err.substr(line + 5));
    double estimate = 0, sigma = 0;
    words >> estimate >> sigma;
    const double fx = camera->camera.params[intrinsic::kFx];
    const double truth_sigma = std::sqrt(camera->covariance->matrix(*camera->covariance->Find("fx"), *camera->covariance->Find("fx")));
    EXPECT_NEAR(estimate, fx, 1e-7 * fx);
    EXPECT_NEAR(sigma, truth_sigma, 1e-3 * truth_sigma);
  }
  ASSERT_TRUE(rig.covariance);
  const size_t pose = r.err.find("right_from_left 1-sigma: rx ");
  ASSERT_NE(pose, std::string::npos) << r.err;
  std::istringstream words(r.err.substr(pose + 28));
  double rx = 0;
  words >> rx;
  const size_t k = *rig.covariance->Find("right_from_left.rx");
  EXPECT_NEAR(rx, std::sqrt(rig.covariance->matrix(k, k)), 1e-2 * std::sqrt(rig.covariance->matrix(k, k)));
}

TEST_F(CliCalibStereo, SolveUsesViewsOfOneCameraAndMatchesByPattern) {
  testing::StereoViews views = testing::SyntheticStereoViews(SolvableRig(), 7, 12);
  views.left.views.pop_back();  // view6: right camera only
  for (View& v : views.left.views) v.name = "cam-a-" + v.name;
  for (View& v : views.right.views) v.name = "cam-b-" + v.name;
  WriteStereoViews(views);
  const CommandResult r = Ok({"solve", "in/l.json", "in/r.json", "--match-views", "(view[0-9]+)$", "-o", "out/rig.json"});
  EXPECT_NE(r.err.find("1 views seen by the right camera only (view6): used for its intrinsics"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("6 views seen by both cameras"), std::string::npos) << r.err;
  // The rig keeps the expression it was given: reproj-report pairs the views again without it.
  EXPECT_EQ(ReadJson("out/rig.json")["view_pairing"]["match_views"], "(view[0-9]+)$");
  const CommandResult report = Run("reproj-report", {"out/rig.json", "in/l.json", "in/r.json", "-o", "out/report.json"});
  ASSERT_EQ(report.exit_code, kOk) << report.err;
  EXPECT_EQ(ReadJson("out/report.json")["stereo"]["views"][0]["name"], "view0");
}

// Issue 24: views named after their files (left-view0 / right-view0, as detect names left01.jpg's
// view left01) are paired with no flag; stderr says the rule and the count; the rig keeps the rule
// and reproj-report on it needs no flag. Names that differ by no left/right token are refused
// with the exact --match-views to use, which then works.
TEST_F(CliCalibStereo, SolvePairsLeftRightNamesByThemselves) {
  testing::StereoViews views = testing::SyntheticStereoViews(SolvableRig(), 7, 12);
  views.left.views.pop_back();  // view6: right camera only
  testing::StereoViews other = views;
  for (View& v : views.left.views) v.name = "left" + v.name.substr(4);  // left0 … left5
  for (View& v : views.right.views) v.name = "right" + v.name.substr(4);
  WriteStereoViews(views);
  const CommandResult r = Ok({"solve", "in/l.json", "in/r.json", "-o", "out/rig.json"});
  EXPECT_NE(r.err.find("calib-stereo: note: paired 6 views by themselves: names differ only by left/right (left0 ↔ right0); "
                       "paired by the number in the name, as --match-views '([0-9]+)$'; the rig keeps this rule"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("6 views seen by both cameras"), std::string::npos) << r.err;
  const Json rig = ReadJson("out/rig.json");
  EXPECT_EQ(rig["view_pairing"]["match_views"], "([0-9]+)$");
  const CommandResult report = Run("reproj-report", {"out/rig.json", "in/l.json", "in/r.json", "-o", "out/report.json"});
  ASSERT_EQ(report.exit_code, kOk) << report.err;
  const Json s = ReadJson("out/report.json")["stereo"];
  EXPECT_EQ(s["views"].size(), 6u);
  EXPECT_EQ(s["views"][0]["name"], "0");
  // Names that differ by "a"/"b": the numbers allow a pairing, which the message spells out.
  for (View& v : other.left.views) v.name = "a_" + v.name;
  for (View& v : other.right.views) v.name = "b_" + v.name;
  WriteStereoViews(other, "in/a.json", "in/b.json");
  EXPECT_TRUE(Fails({"solve", "in/a.json", "in/b.json", "-o", "out/ab.json"}, kBadInput,
                    "in/a.json and in/b.json: views: no view name is in both files and they cannot be paired by themselves: ",
                    {"the names \"a_view0\" and \"b_view0\" do not differ by a left/right token",
                     "pair them by the number in their names with --match-views '([0-9]+)$'"}));
  Ok({"solve", "in/a.json", "in/b.json", "--match-views", "([0-9]+)$", "-o", "out/ab.json"});
  // reproj-report on a rig without a rule says the same.
  Json bare = rig;
  bare.erase("view_pairing");
  WriteJson("in/bare.json", bare);
  const CommandResult hint = Run("reproj-report", {"in/bare.json", "in/a.json", "in/b.json", "-o", "out/r2.json"});
  EXPECT_TRUE(FailsWith(hint, "reproj-report", kBadInput, "in/a.json and in/b.json: views: no view name is in both files",
                        {"pair them by the number in their names with --match-views '([0-9]+)$'"}));
}

// Issue 24 item 4, the wiring (the geometry is stereo_test.RectifiedPairImage): solve --undistort
// writes one side-by-side rectified pair per view both files name images for, 2W × H, with the
// dashed epipolar lines from row 20 every 40 px; without images it is refused and writes nothing.
TEST_F(CliCalibStereo, SolveUndistortWritesRectifiedPairs) {
  const testing::StereoViews views = testing::SyntheticStereoViews(SolvableRig(), 6, 12);
  WriteStereoViews(views);
  EXPECT_TRUE(Fails({"solve", "in/l.json", "in/r.json", "-o", "out/rig.json", "--undistort", "out/pairs"}, kBadInput,
                    "--undistort: no view both cameras saw names its image in in/l.json and in/r.json", {"leave out --undistort"}));
  const int w = views.left.image_size.width, h = views.left.image_size.height;
  ASSERT_TRUE(cv::imwrite(Path("in/grey.png").string(), cv::Mat(h, w, CV_8UC1, cv::Scalar(128))));
  for (const char* file : {"in/l.json", "in/r.json"}) {
    Json c = ReadJson(file);
    for (Json& v : c["views"]) v["image"] = "grey.png";  // beside the correspondences
    WriteJson(file, c);
  }
  const CommandResult r = Ok({"solve", "in/l.json", "in/r.json", "-o", "out/rig.json", "--undistort", "out/pairs"});
  EXPECT_NE(r.err.find("wrote 6 rectified pairs (<view>.rectified.png, left | right, epipolar lines every 40 px) in out/pairs"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(List("out/pairs").size(), 6u);
  const cv::Mat pair = cv::imread(Path("out/pairs/view0.rectified.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(pair.cols, 2 * w);
  ASSERT_EQ(pair.rows, h);
  EXPECT_EQ(pair.at<uint8_t>(20, 0), 0);      // a dash
  EXPECT_EQ(pair.at<uint8_t>(20, 8), 255);    // the gap between two dashes
  EXPECT_EQ(pair.at<uint8_t>(h / 2 + 1, w / 2), 128);  // the grey image, resampled
}

TEST_F(CliCalibStereo, SolveHoldsACameraReadFromAnEarlierCalibration) {
  const StereoRig truth = SolvableRig();
  WriteStereoViews(testing::SyntheticStereoViews(truth, 8, 13));
  WriteText("in/left-cam.json", DumpJson(CameraToJson(truth.left, {"test", {}, std::nullopt})));
  Ok({"solve", "in/l.json", "in/r.json", "--left-camera", "in/left-cam.json", "--hold-left", "-o", "out/rig.json"});
  const StereoRig rig = ReadStereoRig(Path("out/rig.json"));
  for (size_t i = 0; i < truth.left.camera.params.size(); ++i) EXPECT_DOUBLE_EQ(rig.left.camera.params[i], truth.left.camera.params[i]);
  EXPECT_FALSE(rig.left.covariance);
  EXPECT_TRUE(rig.right.covariance);
}

// A volume rig: calib-synth's 9 × 7 grid (80 mm) on five planes 100 mm apart, seen by two 1280×720
// cameras (fx 700, k1 −0.1, k2 0.02) 1.2 m away, each looking at the volume's centre from 1.5° either
// side (a convergent rig, baseline ≈ 73 mm), one world frame for both. Noise-free, the solve gives
// right_from_left = right_from_world · world_from_left of the truth files exactly; with independent
// 0.3 px noise per camera, the error δ = (ω, ρ) of right_from_left (a left perturbation, as the
// covariance's) is consistent with the predicted covariance Σ: each component within 3 σ, δᵀ Σ⁻¹ δ
// between the 0.1 % and 99.9 % points of χ²₆ (0.381 and 22.46: a Σ too small fails the upper, one
// too large the lower), the baseline within 3 of its σ. Fixed seeds: the run is deterministic.
TEST_F(CliCalibStereo, SolveRecoversAVolumeRigWithinItsSigma) {
  const auto synth = [&](const std::string& eye, const std::string& tilt_direction, const std::string& noise, const std::string& seed) {
    Synth("in/" + eye + ".json", {"--image-size", "1280x720", "--fx", "700", "--distortion", "-0.1,0.02,0,0,0", "--grid", "9x7",
                                  "--spacing", "80", "--near", "0", "--far", "400", "--interval", "100", "--camera-distance", "1200",
                                  "--tilt-deg", "1.5", "--tilt-direction-deg", tilt_direction, "--noise", noise, "--seed", seed,
                                  "--camera-name", eye, "--no-test-points", "--truth", "in/" + eye + ".truth.json"});
  };
  const auto truth_pose = [&](const std::string& eye) {
    return *CameraFromJson(JsonDocument::Load(Path("in/" + eye + ".truth.json"))).camera_from_world;
  };
  synth("l", "180", "0", "1");
  synth("r", "0", "0", "2");
  const Rigid3d truth = truth_pose("r") * truth_pose("l").inverse();
  const CommandResult exact = Ok({"solve", "in/l.json", "in/r.json", "-o", "out/exact.json"});
  EXPECT_NE(exact.err.find("the volume (one pose, 5 planes) seen by both cameras"), std::string::npos) << exact.err;
  const StereoRig solved = ReadStereoRig(Path("out/exact.json"));
  EXPECT_LT((solved.right_from_left.R - truth.R).norm(), 1e-9);
  EXPECT_LT((solved.right_from_left.t - truth.t).norm(), 1e-6 * truth.t.norm());

  synth("l", "180", "0.3", "1");
  synth("r", "0", "0.3", "2");
  Ok({"solve", "in/l.json", "in/r.json", "-o", "out/rig.json"});
  const StereoRig rig = ReadStereoRig(Path("out/rig.json"));
  ASSERT_TRUE(rig.covariance);
  ASSERT_EQ(rig.covariance->parameters, std::vector<std::string>(RelativePoseTangentNames().begin(), RelativePoseTangentNames().end()));
  const Eigen::Matrix3d E = rig.right_from_left.R * truth.R.transpose();
  Eigen::Matrix<double, 6, 1> delta;
  delta << RotvecFromRotation(E), rig.right_from_left.t - E * truth.t;
  const Eigen::Matrix<double, 6, 6> sigma = rig.covariance->matrix;
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(delta(i)), 3 * std::sqrt(sigma(i, i))) << rig.covariance->parameters[i];
  const double d2 = delta.dot(sigma.ldlt().solve(delta));
  EXPECT_GT(d2, 0.381);
  EXPECT_LT(d2, 22.46);
  EXPECT_LT(std::abs(rig.baseline() - truth.t.norm()), 3 * *BaselineSigma(rig));
}

TEST_F(CliCalibStereo, SolveRefusesBadInput) {
  const StereoRig truth = SolvableRig();
  testing::StereoViews views = testing::SyntheticStereoViews(truth, 6, 14);
  WriteStereoViews(views);
  const auto solve = [](const std::string& l, const std::string& r, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"solve", l, r, "-o", "out/rig.json"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  // Differing units.
  testing::StereoViews metres = views;
  metres.right.length_unit = LengthUnit::kMetre;
  WriteStereoViews(metres, "in/l.json", "in/r-m.json");
  EXPECT_TRUE(Fails(solve("in/l.json", "in/r-m.json"), kBadInput, "in/l.json and in/r-m.json: length_unit differs (mm vs m)",
                    {"convert one file"}));
  // Too few common views.
  testing::StereoViews few = views;
  for (size_t k = 0; k < 4; ++k) few.right.views[k].name += "x";
  WriteStereoViews(few, "in/l.json", "in/r-few.json");
  EXPECT_TRUE(Fails(solve("in/l.json", "in/r-few.json"), kDegenerate, "2 usable views are seen by both cameras", {"at least 3"}));
  // A view name twice.
  testing::StereoViews twice = views;
  twice.left.views[1].name = twice.left.views[0].name;
  WriteStereoViews(twice, "in/l-twice.json", "in/r.json");
  EXPECT_TRUE(Fails(solve("in/l-twice.json", "in/r.json"), kBadInput, "in/l-twice.json: views[1].name: duplicate view name", {}));
  EXPECT_TRUE(Fails(solve("in/l.json", "in/r.json", {"--match-views", "(view)"}), kBadInput,
                    "in/l.json: views: two views have the key \"view\"", {"unique"}));
  // A held camera of another resolution.
  CalibratedCamera hd = truth.left;
  hd.camera.image_size = {1920, 1080};
  WriteText("in/hd.json", DumpJson(CameraToJson(hd, {"test", {}, std::nullopt})));
  EXPECT_TRUE(Fails(solve("in/l.json", "in/r.json", {"--left-camera", "in/hd.json", "--hold-left"}), kBadInput,
                    "in/l.json: image_size 1280x720 differs from the given camera's 1920x1080", {}));
  // Two image sizes cannot be rectified together.
  testing::StereoViews sizes = views;
  sizes.right.image_size = {1920, 1080};
  WriteStereoViews(sizes, "in/l.json", "in/r-hd.json");
  EXPECT_TRUE(Fails(solve("in/l.json", "in/r-hd.json", {"--rectify"}), kBadInput, "right.image_size", {"one image size"}));
  // Patterns.
  EXPECT_TRUE(Fails(solve("in/l.json", "in/r.json", {"--match-views", "view[0-9]"}), kBadInput, "--match-views", {"has no group"}));
  EXPECT_TRUE(Fails(solve("in/l.json", "in/r.json", {"--match-views", "(x[0-9])"}), kBadInput,
                    "in/l.json: views: the name \"view0\" does not match --match-views", {}));
  EXPECT_TRUE(Fails(solve("in/l.json", "in/r.json", {"--loss", "huber"}), kBadInput, "--loss", {}));
}

// One camera's views given for both cameras (issue 24: exit 0 with baseline 0, which export then
// refused): the same file twice is refused before any work, and two copies of one file, solved,
// give coinciding cameras, refused as degenerate.
TEST_F(CliCalibStereo, SolveRefusesOneCameraGivenTwice) {
  WriteStereoViews(testing::SyntheticStereoViews(SolvableRig(), 6, 15));
  EXPECT_TRUE(Fails({"solve", "in/l.json", "in/l.json", "-o", "out/rig.json"}, kBadInput,
                    "in/l.json and in/l.json: are the same file", {"the right camera's"}));
  EXPECT_TRUE(Fails({"solve", "in/l.json", "./in/../in/l.json", "-o", "out/rig.json"}, kBadInput,
                    "in/l.json and ./in/../in/l.json: are the same file", {}));
  WriteText("in/copy.json", ReadText("in/l.json"));
  EXPECT_TRUE(Fails({"solve", "in/l.json", "in/copy.json", "-o", "out/rig.json"}, kDegenerate,
                    "in/l.json and in/copy.json: the solved cameras coincide", {"one camera's views"}));
}

}  // namespace
}  // namespace vstcal::cli_test
