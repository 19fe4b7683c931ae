// CLI tests of calib-convert with ROS camera_info and Kalibr camchain.yaml (issue 26 items 2 and 5):
// the hand-written samples of tests/data read by key, not by name; converted files are fixed points
// (written, read and written again: the same bytes); PyYAML, the YAML reader of Kalibr and of ROS's
// Python tools, reads what vstcal writes as floats, integers and strings of the right shapes; and
// every bad file gives exit code 2, one line naming the file, the field and the fix, and no output.
#include <fstream>
#include <ostream>
#include <sstream>

#include "cli_fixture.h"
#include "convert_bad_input.h"

namespace vstcal::cli_test {
namespace {

constexpr std::string_view kTool = "calib-convert";

std::string Sample(const std::string& relative) {
  std::ifstream in(std::string(VSTCAL_SOURCE_DIR) + "/tests/data/" + relative);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `text` with its only occurrence of `from` replaced by `to`.
std::string Edit(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos) {
    throw std::runtime_error("test bug: \"" + from + "\" does not occur exactly once");
  }
  return text.replace(at, from.size(), to);
}

class CliConvertInterop : public CliTest {
 protected:
  CommandResult Convert(const std::vector<std::string>& args) {
    const CommandResult r = Run(kTool, args);
    EXPECT_EQ(r.exit_code, kOk) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    return r;
  }
  // The file at `relative` without its first line (the provenance comment, which names the command).
  std::string Body(const std::string& relative) {
    const std::string t = ReadText(relative);
    return t.substr(t.find('\n') + 1);
  }
  // PyYAML's view of a written file, checked by `check` (Python, with `d` the loaded document).
  void PyYamlAccepts(const std::string& relative, const std::string& check) {
    WriteText("check.py", "import sys, yaml\nd = yaml.safe_load(open(sys.argv[1]))\n" + check + "\nprint('ok')\n");
    const CommandResult r = RunCommand({"/usr/bin/python3", Path("check.py").string(), Path(relative).string()});
    EXPECT_EQ(r.exit_code, 0) << relative << "\n" << r.out << r.err;
  }
};

// ROS: the monocular sample is told apart from OpenCV YAML by its keys, becomes a camera@1 with its
// numbers exactly, and camera@1 → ROS → camera@1 → ROS gives the same bytes twice.
TEST_F(CliConvertInterop, RosCameraInfoRoundTripIsAFixedPoint) {
  WriteText("in/ost.yaml", Sample("ros/mono_plumb_bob.yaml"));
  const CommandResult r = Convert({"in/ost.yaml", "-o", "out/cam.json"});
  EXPECT_NE(r.err.find("note: in/ost.yaml: rectification_matrix, projection_matrix"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("wrote out/cam.json (vstcal/camera@1)"), std::string::npos) << r.err;
  const Json cam = ReadJson("out/cam.json");
  EXPECT_EQ(cam.at("camera"), "narrow_stereo");
  EXPECT_EQ(cam.at("K").at(0).at(0).get<double>(), 423.10428);
  EXPECT_EQ(cam.at("distortion").at("k1").get<double>(), -0.322543);
  Convert({"out/cam.json", "--to", "ros", "-o", "out/a.yaml"});
  Convert({"out/a.yaml", "-o", "out/b.json"});
  Convert({"out/b.json", "--to", "ros", "-o", "out/c.yaml"});
  EXPECT_EQ(Body("out/a.yaml"), Body("out/c.yaml"));
  PyYamlAccepts("out/a.yaml",
                "assert d['image_width'] == 640 and d['camera_name'] == 'narrow_stereo'\n"
                "assert d['distortion_model'] == 'plumb_bob'\n"
                "for k, n in [('camera_matrix', 9), ('distortion_coefficients', 5), ('rectification_matrix', 9),"
                " ('projection_matrix', 12)]:\n"
                "    assert len(d[k]['data']) == n and d[k]['rows'] * d[k]['cols'] == n, k\n"
                "    assert all(type(x) is float for x in d[k]['data']), k\n"
                "assert d['camera_matrix']['data'][0] == 423.10428");
}

// Kalibr: the stereo sample becomes a stereo@1 rig in metres; rig → camchain → rig → camchain gives
// the same bytes twice, which PyYAML reads with T_cn_cnm1 as four rows of four floats.
TEST_F(CliConvertInterop, KalibrChainOfTwoIsARigAndAFixedPoint) {
  WriteText("in/camchain.yaml", Sample("kalibr/camchain_stereo.yaml"));
  const CommandResult r = Convert({"in/camchain.yaml", "-o", "out/rig.json"});
  EXPECT_NE(r.err.find("note: in/camchain.yaml: cam0.T_cam_imu: not read"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(vstcal/stereo@1, a stereo rig)"), std::string::npos) << r.err;
  const Json rig = ReadJson("out/rig.json");
  EXPECT_EQ(rig.at("format"), "vstcal/stereo@1");
  EXPECT_EQ(rig.at("length_unit"), "m");
  EXPECT_EQ(rig.at("right_from_left").at("t").at(0).get<double>(), -0.110073808127187);
  EXPECT_EQ(rig.at("left").at("K").at(0).at(2).get<double>(), 367.215);
  Convert({"out/rig.json", "--to", "kalibr", "-o", "out/a.yaml"});
  Convert({"out/a.yaml", "-o", "out/b.json"});
  Convert({"out/b.json", "--to", "kalibr", "-o", "out/c.yaml"});
  EXPECT_EQ(Body("out/a.yaml"), Body("out/c.yaml"));
  PyYamlAccepts("out/a.yaml",
                "assert sorted(d) == ['cam0', 'cam1']\n"
                "T = d['cam1']['T_cn_cnm1']\n"
                "assert len(T) == 4 and all(len(r) == 4 and all(type(x) is float for x in r) for r in T)\n"
                "assert T[0][3] == -0.110073808127187 and T[3] == [0.0, 0.0, 0.0, 1.0]\n"
                "for c in d.values():\n"
                "    assert c['camera_model'] == 'pinhole' and c['distortion_model'] == 'radtan'\n"
                "    assert len(c['intrinsics']) == 4 and len(c['distortion_coeffs']) == 4\n"
                "    assert c['resolution'] == [752, 480]\n"
                "assert d['cam0']['distortion_coeffs'][3] == 1.76187114e-05");
}

// A stereo@1 rig in mm as ROS: a left and a right camera_info, P's last column in metres.
TEST_F(CliConvertInterop, RigToRosGivesLeftAndRight) {
  WriteText("in/camchain.yaml", Sample("kalibr/camchain_stereo.yaml"));
  Convert({"in/camchain.yaml", "-o", "out/rig.json"});
  const CommandResult r = Convert({"out/rig.json", "--to", "ros", "-o", "out/left.yaml", "--output-right", "out/right.yaml"});
  EXPECT_NE(r.err.find("wrote out/left.yaml and out/right.yaml (ROS camera_info YAML, a stereo rig)"), std::string::npos)
      << r.err;
  PyYamlAccepts("out/right.yaml",
                "P = d['projection_matrix']['data']\n"
                "B = -P[3] / P[0]\n"
                "assert d['camera_name'] == 'right'\n"
                "t = (-0.110073808127187, 0.000399121547014, -0.000853702503357)  # the sample's T_cn_cnm1, m\n"
                "assert abs(B - sum(x * x for x in t) ** 0.5) < 1e-12, B\n"
                "assert P[7] == 0.0 and P[11] == 0.0");
  PyYamlAccepts("out/left.yaml", "P = d['projection_matrix']['data']\nassert P[3] == 0.0 and d['camera_name'] == 'left'");
  // Each camera_info reads back as a camera (its rectification said not kept).
  const CommandResult back = Convert({"out/right.yaml", "-o", "out/right.json"});
  EXPECT_NE(back.err.find("rectification_matrix, projection_matrix"), std::string::npos) << back.err;
}

TEST_F(CliConvertInterop, SameInputSameBytes) {
  WriteText("in/camchain.yaml", Sample("kalibr/camchain_stereo.yaml"));
  EXPECT_TRUE(SameBytesTwice(kTool, {"in/camchain.yaml", "--to", "ros", "-o", "out/l.yaml", "--output-right", "out/r.yaml"},
                             {"out/l.yaml", "out/r.yaml"}));
}

std::vector<BadInput> BadRos() {
  const std::string y = Sample("ros/mono_plumb_bob.yaml");
  const std::string k = "  data: [423.10428, 0.0, 309.05867, 0.0, 424.08911, 227.45914, 0.0, 0.0, 1.0]\n";
  return {
      {"MissingCameraMatrix", "c.yaml", Edit(y, "camera_matrix:\n  rows: 3\n  cols: 3\n" + k, ""), {},
       "in/c.yaml: camera_matrix: ", {"missing field", "add the 3×3 camera matrix K"}},
      {"CameraMatrixMisSized", "c.yaml", Edit(y, "camera_matrix:\n  rows: 3\n  cols: 3\n", "camera_matrix:\n  rows: 2\n  cols: 3\n"),
       {}, "in/c.yaml: camera_matrix: ", {"expected 3×3, got 2×3", "write rows: 3, cols: 3"}},
      {"CameraMatrixShortData", "c.yaml", Edit(y, k, "  data: [423.1, 0.0, 309.0, 0.0, 424.0, 227.4, 0.0, 0.0]\n"), {},
       "in/c.yaml: camera_matrix.data: ", {"expected 9 numbers, got 8"}},
      {"NotANumber", "c.yaml", Edit(y, "423.10428, 0.0, 309.05867", ".nan, 0.0, 309.05867"), {},
       "in/c.yaml: camera_matrix.data[0]: ", {"the number .nan is not finite", "write a finite number"}},
      {"Infinite", "c.yaml", Edit(y, "-0.322543", "-1e999"), {}, "in/c.yaml: distortion_coefficients.data[0]: ",
       {"beyond the doubles"}},
      {"UnknownModel", "c.yaml", Edit(y, "distortion_model: plumb_bob", "distortion_model: kannala_brandt"), {},
       "in/c.yaml: distortion_model: ", {"unknown distortion model \"kannala_brandt\"", "plumb_bob", "rational_polynomial"}},
      {"EquidistantWithFive", "c.yaml", Edit(Sample("ros/equidistant.yaml"), "  cols: 4\n  data: [-0.0071", "  cols: 5\n  data: [-0.0071"), {},
       "in/c.yaml: distortion_coefficients: ", {"expected 1×4, got 1×5"}},
      {"PlumbBobWithFour", "c.yaml", Edit(y, "  cols: 5\n  data: [-0.322543, 0.104152, -0.000386, 0.000593, 0.0]",
                                          "  cols: 4\n  data: [-0.322543, 0.104152, -0.000386, 0.000593]"),
       {}, "in/c.yaml: distortion_coefficients: ", {"expected 1×5, got 1×4"}},
      {"MissingProjection", "c.yaml", y.substr(0, y.find("projection_matrix:")), {}, "in/c.yaml: projection_matrix: ",
       {"missing field", "[K | 0] for one camera"}},
      {"RectificationNotARotation", "c.yaml",
       Edit(y, "  data: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]", "  data: [2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]"),
       {}, "in/c.yaml: rectification_matrix: ", {"not a rotation matrix"}},
      {"DuplicateKey", "c.yaml", y + "image_width: 320\n", {}, "in/c.yaml: line 21, column 1: ",
       {"the key \"image_width\" appears a second time"}},
      {"Syntax", "c.yaml", Edit(y, "distortion_model: plumb_bob", "distortion_model: [plumb_bob"), {}, "in/c.yaml: line ",
       {"not valid YAML"}},
  };
}

std::vector<BadInput> BadKalibr() {
  const std::string y = Sample("kalibr/camchain_stereo.yaml");
  const std::string three = Sample("kalibr/camchain_three.yaml");
  return {
      {"ThreeCamerasAsStereo", "c.yaml", three, {}, "in/c.yaml: cam2: ",
       {"a chain of 3 cameras, and a vstcal/stereo@1 rig holds two", "delete cam2"}, "out/rig.json"},
      {"ThreeCamerasAsKalibr", "c.yaml", three, {"--to", "kalibr"}, "in/c.yaml: cam2: ", {"a chain of 3 cameras"},
       "out/c.yaml"},
      {"MissingIntrinsics", "c.yaml", Edit(y, "  intrinsics: [458.654, 457.296, 367.215, 248.375]\n", ""), {},
       "in/c.yaml: cam0.intrinsics: ", {"missing field", "[fu, fv, pu, pv]"}},
      {"IntrinsicsThree", "c.yaml", Edit(y, "[458.654, 457.296, 367.215, 248.375]", "[458.654, 457.296, 367.215]"), {},
       "in/c.yaml: cam0.intrinsics: ", {"expected 4 numbers, got 3"}},
      {"RadtanFive", "c.yaml",
       Edit(y, "[-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]", "[-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05, 0.1]"),
       {}, "in/c.yaml: cam0.distortion_coeffs: ", {"expected 4 numbers, got 5", "[k1, k2, r1, r2]"}},
      {"Fov", "c.yaml", Edit(y, "  distortion_model: radtan\n  intrinsics: [458", "  distortion_model: fov\n  intrinsics: [458"),
       {}, "in/c.yaml: cam0.distortion_model: ", {"\"fov\" model has no vstcal lens model"}},
      {"Omni", "c.yaml", Edit(y, "  camera_model: pinhole\n  distortion_coeffs: [-0.28340811", "  camera_model: omni\n  distortion_coeffs: [-0.28340811"),
       {}, "in/c.yaml: cam0.camera_model: ", {"camera model \"omni\" has no vstcal model", "pinhole-radtan"}},
      {"MissingTransform", "c.yaml", Edit(y, "cam1:\n  T_cn_cnm1:\n", "cam1:\n  T_old:\n"), {}, "in/c.yaml: cam1.T_cn_cnm1: ",
       {"missing field"}},
      {"TransformNotRigid", "c.yaml", Edit(y, "  - [0.0, 0.0, 0.0, 1.0]\n  cam_overlaps: [0]", "  - [0.0, 0.0, 1.0, 1.0]\n  cam_overlaps: [0]"),
       {}, "in/c.yaml: cam1.T_cn_cnm1[3]: ", {"the last row of a rigid transform is [0, 0, 0, 1]"}},
      {"ResolutionNegative", "c.yaml", Edit(y, "  resolution: [752, 480]\n  rostopic: /cam0", "  resolution: [-752, 480]\n  rostopic: /cam0"),
       {}, "in/c.yaml: cam0.resolution[0]: ", {"width"}},
      {"GapInCameras", "c.yaml", Edit(y, "cam1:", "cam2:"), {}, "in/c.yaml: cam2: ", {"comes after a missing cam1"}},
      {"NonFinite", "c.yaml", Edit(y, "[457.587, 456.134", "[.inf, 456.134"), {}, "in/c.yaml: cam1.intrinsics[0]: ",
       {"the number .inf is not finite"}},
  };
}

std::vector<BadInput> BadUsage() {
  const std::string kalibr = Sample("kalibr/camchain_stereo.yaml");
  return {
      {"RigToRosWithoutRight", "c.yaml", kalibr, {"--to", "ros"}, "--output-right: ", {"missing", "give the right camera's file"},
       "out/l.yaml"},
      {"OutputRightForACamera", "c.yaml", Sample("ros/mono_plumb_bob.yaml"), {"--output-right", "out/r.yaml"},
       "--output-right: ", {"applies to a stereo rig written as ROS camera_info only"}},
      {"RigToOpenCv", "c.yaml", kalibr, {"--to", "opencv"}, "in/c.yaml: ", {"a stereo rig", "calib-stereo export"}, "out/c.yaml"},
      {"RigToMrcal", "c.yaml", kalibr, {}, "in/c.yaml: ", {"a stereo rig", "calib-stereo export"}, "out/c.cameramodel"},
      {"RosToCameramodelExtension", "c.yaml", Sample("ros/mono_plumb_bob.yaml"), {"--to", "ros"}, "--to: ",
       {"contradicts the output's name"}, "out/c.cameramodel"},
  };
}

INSTANTIATE_TEST_SUITE_P(Ros, CliCalibConvertBad, ::testing::ValuesIn(BadRos()),
                         [](const auto& instance) { return instance.param.name; });
INSTANTIATE_TEST_SUITE_P(Kalibr, CliCalibConvertBad, ::testing::ValuesIn(BadKalibr()),
                         [](const auto& instance) { return instance.param.name; });
INSTANTIATE_TEST_SUITE_P(InteropUsage, CliCalibConvertBad, ::testing::ValuesIn(BadUsage()),
                         [](const auto& instance) { return instance.param.name; });

}  // namespace
}  // namespace vstcal::cli_test
