// CLI tests of calib-stereo: rigs assembled from two cameras and exported to OpenCV and mrcal,
// binocular registration of tracked sequences, display planning; every bad input gives its
// documented exit code, one line naming the file, the field and the fix, and no output file.
#include "cli_fixture.h"
#include "support/stereo_rigs.h"
#include "vstcal/io/camera_io.h"
#include "vstcal/io/stereo_io.h"

namespace vstcal::cli_test {
namespace {

constexpr std::string_view kTool = "calib-stereo";

class CliCalibStereo : public CliTest {
 protected:
  // in/left.json and in/right.json: the ZED-like rig's cameras (camera@1, no pose), and in/rig.json.
  void WriteInputs() {
    const StereoRig rig = testing::ZedLikeRig();
    const io::Provenance p{"test", {}, std::nullopt};
    WriteText("in/left.json", io::DumpJson(io::CameraToJson(rig.left, p)));
    WriteText("in/right.json", io::DumpJson(io::CameraToJson(rig.right, p)));
    WriteText("in/rig.json", io::DumpJson(io::StereoRigToJson(rig, p)));
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
  const io::Provenance p{"test", {}, std::nullopt};
  WriteText("in/left-posed.json", io::DumpJson(io::CameraToJson(left, p)));
  WriteText("in/right-posed.json", io::DumpJson(io::CameraToJson(right, p)));
  Ok({"assemble", "in/left-posed.json", "in/right-posed.json", "--rectify", "--alpha", "0", "-o", "out/rig.json"});
  const StereoRig back = io::ReadStereoRig(Path("out/rig.json"));
  EXPECT_LT((back.right_from_left.t - rig.right_from_left.t).norm(), 1e-9);
  ASSERT_TRUE(back.rectification.has_value());
  EXPECT_EQ(back.rectification->alpha, 0.0);
  // A camera in metres cannot be composed with one in millimetres.
  right.length_unit = LengthUnit::kMetre;
  WriteText("in/right-m.json", io::DumpJson(io::CameraToJson(right, p)));
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
  WriteText("in/right-hd.json", io::DumpJson(io::CameraToJson(right, {"test", {}, std::nullopt})));
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

}  // namespace
}  // namespace vstcal::cli_test
