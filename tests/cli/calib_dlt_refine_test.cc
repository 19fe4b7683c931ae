// CLI tests of calib-dlt --refine: the DLT camera refined to maximum likelihood (distortion,
// robust loss, covariance, projection uncertainty) against calib-synth's truth within the σ the
// tool reports; the refinement's flags without --refine, its failures; and the covariance block
// of a camera@1 file as calib-compare and calib-convert read it back (every malformation refused
// with exit code 2 and one line naming the entry).
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <ostream>

#include "calibration_checks.h"
#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

constexpr std::string_view kTool = "calib-dlt";

// DistortedVolumeArgs() with seed 000's test points.
std::vector<std::string> VolumeArgs() { return Remove(DistortedVolumeArgs(), "--no-test-points", false); }

const std::vector<std::string> kDefaultTerms = {"fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"};

class CliCalibDltRefine : public CliTest {
 protected:
  // Runs calib-dlt in/volume.json -o out/camera.json --refine [args]; the run must succeed.
  Json Refine(std::vector<std::string> args = {}) {
    args.insert(args.begin(), {"in/volume.json", "-o", "out/camera.json", "--refine"});
    last_ = Run(kTool, args);
    EXPECT_EQ(last_.exit_code, kOk) << last_.err;
    if (last_.exit_code != kOk) throw std::runtime_error("calib-dlt failed: " + last_.err);
    return ReadJson("out/camera.json");
  }

  CommandResult last_;
};

TEST_F(CliCalibDltRefine, RecoversTheTruthWithinFiveSigma) {
  Synth("in/volume.json", VolumeArgs());
  const Json camera = Refine();
  const Json truth = ReadJson("in/volume.truth.json");
  EXPECT_EQ(camera.at("method"), "dlt+refine");
  EXPECT_TRUE(camera.contains("dlt"));  // the start's diagnostics are kept
  EXPECT_EQ(camera.at("refinement").at("status"), "converged");
  // The DLT's pinhole is promoted to radial-tangential for the named terms; its skew is dropped.
  EXPECT_EQ(camera.at("distortion").at("model"), "radial-tangential");
  EXPECT_EQ(camera.at("distortion").at("k3"), 0.0);
  EXPECT_EQ(camera.at("K")[0][1], 0.0);
  EXPECT_TRUE(CovarianceIsWellFormed(camera));
  EXPECT_EQ(camera.at("covariance").at("parameters"),
            Json({"fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "camera_from_world.rx", "camera_from_world.ry",
                  "camera_from_world.rz", "camera_from_world.tx", "camera_from_world.ty", "camera_from_world.tz"}));
  EXPECT_TRUE(WithinSigmas(camera, truth, kDefaultTerms, 5));
  // The refined P is K [R | t] of the refined camera (the DLT's P is not kept).
  const Pinhole p = Pinhole::FromTruth(camera);
  Eigen::Matrix<double, 3, 4> Rt;
  Rt << p.R, p.t;
  Eigen::Matrix<double, 3, 4> KRt = p.K * Rt;
  KRt /= KRt.row(2).head<3>().norm();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(camera.at("P")[r][c].get<double>(), KRt(r, c), 1e-9 * KRt.cwiseAbs().maxCoeff());
  }
  // With the lens modelled, the reprojection RMS drops below the DLT's (which has no distortion).
  ASSERT_EQ(Run(kTool, {"in/volume.json", "-o", "out/dlt.json"}).exit_code, kOk);
  const Json dlt = ReadJson("out/dlt.json");
  EXPECT_LT(camera.at("fit").at("rms_px").get<double>(), dlt.at("fit").at("rms_px").get<double>());
  EXPECT_FALSE(dlt.contains("refinement"));
  // The unrefined DLT camera carries its own first-order covariance over its 11 parameters.
  EXPECT_EQ(dlt.at("covariance").at("parameters"),
            Json({"fx", "fy", "cx", "cy", "s", "camera_from_world.rx", "camera_from_world.ry", "camera_from_world.rz",
                  "camera_from_world.tx", "camera_from_world.ty", "camera_from_world.tz"}));
}

TEST_F(CliCalibDltRefine, StartsFromDltNotTsai) {
  // The same optimum from either closed form (to far below σ), but recorded as its own method.
  Synth("in/volume.json", VolumeArgs());
  const Json dlt = Refine();
  ASSERT_EQ(Run("calib-tsai", {"in/volume.json", "-o", "out/tsai.json", "-q"}).exit_code, kOk);
  const Json tsai = ReadJson("out/tsai.json");
  EXPECT_EQ(tsai.at("method"), "tsai+refine");
  for (const std::string& p : kDefaultTerms) {
    EXPECT_NEAR(LensParameter(dlt, p), LensParameter(tsai, p), 1e-3 * Sigma(dlt, p)) << p;
  }
}

TEST_F(CliCalibDltRefine, PinholeWithSkewIsTheDltModelRefined) {
  // --distortion none --skew: the DLT's own 11 parameters, now maximum likelihood.
  Synth("in/volume.json", Override(Override(VolumeArgs(), "--distortion", "0,0,0,0,0"), "--skew-deg", "89.5"));
  const Json camera = Refine({"--distortion", "none", "--skew"});
  EXPECT_EQ(camera.at("distortion").at("model"), "none");
  EXPECT_EQ(camera.at("refinement").at("free_intrinsics"), Json({"fx", "fy", "cx", "cy", "s"}));
  EXPECT_TRUE(WithinSigmas(camera, ReadJson("in/volume.truth.json"), {"fx", "fy", "cx", "cy", "s"}, 5));
}

TEST_F(CliCalibDltRefine, OutlierListedAndUncertaintyReported) {
  Json doc = Synth("in/volume.json", VolumeArgs());
  doc["views"][0]["points"][10][4] = doc["views"][0]["points"][10][4].get<double>() - 25;
  WriteJson("in/volume.json", doc);
  const Json camera = Refine({"--loss", "huber", "--uncertainty-at", "0,0,200", "--uncertainty-pixel", "320,240,1000",
                              "--uncertainty-grid", "1200", "--grid-size", "8x6"});
  const Json& outliers = camera.at("refinement").at("outliers");
  ASSERT_EQ(outliers.size(), 1u);
  EXPECT_EQ(outliers[0].at("view"), "plane-00");
  EXPECT_EQ(outliers[0].at("point_index"), 10);
  EXPECT_NE(last_.err.find("calib-dlt: warning: outlier: views[0].points[10] (view \"plane-00\")"), std::string::npos)
      << last_.err;
  const Json& u = camera.at("projection_uncertainty");
  EXPECT_EQ(u.at("test_points").size(), 5u);
  EXPECT_EQ(u.at("world_points").size(), 1u);
  EXPECT_EQ(u.at("pixels").size(), 1u);
  EXPECT_EQ(u.at("grid").at("cells").size(), 48u);
}

// Without --refine the DLT camera has its first-order covariance (docs/math/dlt.md#covariance):
// the summary lists each parameter's value as written with the σ of dlt.uncertainty, the file
// has Cov(P) in its stated gauge (rank 11) and the projection uncertainty at the test points.
TEST_F(CliCalibDltRefine, WithoutRefineTheDltCovarianceIsReported) {
  Synth("in/volume.json", Override(VolumeArgs(), "--distortion", "0,0,0,0,0"));
  const CommandResult r = Run(kTool, {"in/volume.json", "-o", "out/camera.json", "--uncertainty-pixel", "320,240,1000"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json camera = ReadJson("out/camera.json");
  ASSERT_TRUE(camera.contains("covariance"));
  EXPECT_TRUE(CovarianceIsWellFormed(camera));
  const Json& u = camera.at("dlt").at("uncertainty");
  EXPECT_GT(u.at("sigma_px").get<double>(), 0);
  EXPECT_EQ(u.at("dof").get<int>(), 2 * camera.at("fit").at("n_points").get<int>() - 11);
  EXPECT_EQ(u.at("P_covariance").at("matrix").size(), 12u);
  EXPECT_EQ(camera.at("projection_uncertainty").at("test_points").size(), 5u);
  EXPECT_EQ(camera.at("projection_uncertainty").at("pixels").size(), 1u);
  const std::map<std::string, double> k = {{"fx", camera["K"][0][0]}, {"fy", camera["K"][1][1]},
                                           {"cx", camera["K"][0][2]}, {"cy", camera["K"][1][2]},
                                           {"s", camera["K"][0][1]}};
  for (const auto& [name, value] : k) {
    const size_t at = r.err.find("\n  " + name + " ");
    ASSERT_NE(at, std::string::npos) << name << "\n" << r.err;
    const std::string line = r.err.substr(at + 1, r.err.find('\n', at + 1) - at - 1);
    EXPECT_NEAR(std::stod(line.substr(2 + name.size())), value, 1e-7 * std::max(1.0, std::abs(value))) << line;
    EXPECT_EQ(line.find("(no covariance)"), std::string::npos) << line;
    EXPECT_NE(line.find('['), std::string::npos) << line;
    EXPECT_NEAR(Sigma(camera, name), u.at("sigma").at(name).get<double>(), 1e-9 * Sigma(camera, name)) << name;
  }
  // The truth lies within 5σ of the DLT estimate.
  EXPECT_TRUE(WithinSigmas(camera, ReadJson("in/volume.truth.json"), {"fx", "fy", "cx", "cy"}, 5));
}

// --reject-views on a volume (docs/tools/calib-dlt.md): one template position whose world
// coordinates are off by one square (60 mm) is rejected and named, and the camera is the DLT of the
// other positions; without the flag it is kept and the fit is far worse.
TEST_F(CliCalibDltRefine, RejectViewsDropsAShiftedTemplatePosition) {
  Json doc = Synth("in/volume.json", Override(Override(VolumeArgs(), "--distortion", "0,0,0,0,0"), "--noise", "0.3"));
  ASSERT_GE(doc["views"].size(), 4u);
  for (Json& p : doc["views"][1]["points"]) p[0] = p[0].get<double>() + 60;
  WriteJson("in/volume.json", doc);
  const CommandResult r = Run(kTool, {"in/volume.json", "-o", "out/camera.json", "--reject-views"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json camera = ReadJson("out/camera.json");
  const Json& rejected = camera.at("view_rejection").at("rejected");
  ASSERT_EQ(rejected.size(), 1u) << rejected.dump();
  EXPECT_EQ(rejected[0].at("view_index"), 1);
  EXPECT_NE(r.err.find("calib-dlt: warning: --reject-views: rejected view \"" + doc["views"][1]["name"].get<std::string>()),
            std::string::npos)
      << r.err;
  Json without = doc;
  without["views"].erase(1);
  WriteJson("in/without.json", without);
  ASSERT_EQ(Run(kTool, {"in/without.json", "-o", "out/without.json", "-q"}).exit_code, kOk);
  EXPECT_EQ(camera.at("K"), ReadJson("out/without.json").at("K"));
  ASSERT_EQ(Run(kTool, {"in/volume.json", "-o", "out/kept.json", "-q"}).exit_code, kOk);
  EXPECT_GT(ReadJson("out/kept.json")["fit"]["rms_px"].get<double>(), 5 * camera["fit"]["rms_px"].get<double>());
}

TEST_F(CliCalibDltRefine, WithoutRefineTheRefinementFlagsAreRefused) {
  Synth("in/volume.json", VolumeArgs());
  for (const std::vector<std::string>& flag : std::vector<std::vector<std::string>>{{"--distortion", "k1"},
                                                                                    {"--skew"},
                                                                                    {"--loss", "huber"},
                                                                                    {"--loss-scale", "2"},
                                                                                    {"--max-iterations", "50"}}) {
    std::vector<std::string> args = {"in/volume.json", "-o", "out/camera.json"};
    args.insert(args.end(), flag.begin(), flag.end());
    EXPECT_TRUE(
        FailsWith(Run(kTool, args), kTool, kBadInput, flag[0] + " requires --refine", {"see calib-dlt --help"}));
  }
  EXPECT_TRUE(OutDirEmpty());
}

struct BadRefine {
  std::string name;
  int exit_code;
  std::vector<std::string> flags;
  std::string location;  // after "calib-dlt: error: "
  std::vector<std::string> phrases;
  std::function<void(Json& doc)> edit = [](Json&) {};
};

void PrintTo(const BadRefine& c, std::ostream* os) { *os << c.name; }

class CliCalibDltRefineBad : public CliTest, public ::testing::WithParamInterface<BadRefine> {};

TEST_P(CliCalibDltRefineBad, FailsWithOneLineAndNoOutput) {
  const BadRefine& c = GetParam();
  Json doc = Synth("in/volume.json", VolumeArgs());
  c.edit(doc);
  WriteJson("in/volume.json", doc);
  std::vector<std::string> args = {"in/volume.json", "-o", "out/camera.json", "--refine", "--residuals", "out/r.json"};
  args.insert(args.end(), c.flags.begin(), c.flags.end());
  const auto r = Run(kTool, args);
  EXPECT_TRUE(FailsWith(r, kTool, c.exit_code, c.location, c.phrases));
  EXPECT_EQ(r.err.rfind("calib-dlt: error: " + c.location, 0), 0u) << r.err;
  EXPECT_TRUE(OutDirEmpty());
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliCalibDltRefineBad,
    ::testing::Values(
        BadRefine{"NoConvergence",
                  kDegenerate,
                  {"--max-iterations", "1"},
                  "in/volume.json: ",
                  {"the refinement did not converge in 1 iterations", "raise --max-iterations"}},
        BadRefine{"UnknownDistortionTerm",
                  kBadInput,
                  {"--distortion", "k1,p3"},
                  "--distortion: ",
                  {"unknown term \"p3\"", "did you mean \"p1\"?"}},
        BadRefine{"PixelOutsideTheImage",
                  kBadInput,
                  {"--uncertainty-pixel", "-1,100,1000"},
                  "--uncertainty-pixel: ",
                  {"(-1, 100) lies outside the 640×480 image"}},
        BadRefine{"ZeroGridDepth", kBadInput, {"--uncertainty-grid", "0"}, "--uncertainty-grid: ", {"positive"}},
        BadRefine{"PointBehindTheCamera",
                  kBadInput,
                  {},
                  "in/volume.json: ",
                  {"1 of 315 points lie behind the camera", "views[3].points[2]"},
                  [](Json& d) { d["views"][3]["points"][2][2] = -5000.0; }}),
    [](const auto& param_info) { return param_info.param.name; });

// ---------------------------------------------------------------------------------------------
// The covariance block read back: calib-compare and calib-convert both refuse a malformed one.

struct BadCovariance {
  std::string name;
  std::string field;  // after "in/camera.json: "
  std::vector<std::string> phrases;
  std::function<void(Json& covariance)> edit;
  std::function<void(Json& camera)> edit_camera = [](Json&) {};  // the rest of the file
  bool planar = false;  // a planar-views camera from calib-tsai (its covariance has pose blocks)
};

void PrintTo(const BadCovariance& c, std::ostream* os) { *os << c.name; }

class CliBadCovariance : public CliTest, public ::testing::WithParamInterface<BadCovariance> {};

TEST_P(CliBadCovariance, IsRefusedByCompareAndConvert) {
  const BadCovariance& c = GetParam();
  const std::string truth = c.planar ? "in/views.truth.json" : "in/volume.truth.json";
  if (c.planar) {
    Synth("in/views.json", PlanarArgs());
    ASSERT_EQ(Run("calib-tsai", {"in/views.json", "-o", "in/good.json", "-q"}).exit_code, kOk);
  } else {
    Synth("in/volume.json", VolumeArgs());
    ASSERT_EQ(Run(kTool, {"in/volume.json", "-o", "in/good.json", "--refine", "-q"}).exit_code, kOk);
  }
  // The good file is read back by both tools.
  ASSERT_EQ(Run("calib-compare", {truth, "in/good.json"}).exit_code, kOk);
  ASSERT_EQ(Run("calib-convert", {"in/good.json", "-o", "in/again.json"}).exit_code, kOk);
  EXPECT_EQ(ReadJson("in/again.json").at("covariance"), ReadJson("in/good.json").at("covariance"));

  Json camera = ReadJson("in/good.json");
  c.edit(camera.at("covariance"));
  c.edit_camera(camera);
  WriteJson("in/camera.json", camera);
  const std::string location = "in/camera.json: " + c.field + ": ";
  EXPECT_TRUE(FailsWith(Run("calib-compare", {truth, "in/camera.json"}), "calib-compare", kBadInput,
                        location, c.phrases));
  EXPECT_TRUE(FailsWith(Run("calib-convert", {"in/camera.json", "-o", "out/camera.yaml"}), "calib-convert", kBadInput,
                        location, c.phrases));
  EXPECT_TRUE(OutDirEmpty());
}

// The good covariance names fx, fy, cx, cy, k1, k2, p1, p2, camera_from_world.rx … tz (14).
INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadCovariance,
    ::testing::Values(
        BadCovariance{"NotSymmetric",
                      "covariance.matrix[1][0]",
                      {"differs from matrix[0][1]: not symmetric", "write a symmetric covariance matrix"},
                      [](Json& c) { c["matrix"][1][0] = 2 * c["matrix"][0][1].get<double>() + 1; }},
        BadCovariance{"NegativeVariance",
                      "covariance.matrix[3][3]",
                      {"the variance of \"cy\" is negative"},
                      [](Json& c) { c["matrix"][3][3] = -1.0; }},
        BadCovariance{
            "MissingRow", "covariance.matrix", {"expected 14 items, got 13"}, [](Json& c) { c["matrix"].erase(13); }},
        BadCovariance{"ShortRow",
                      "covariance.matrix[2]",
                      {"expected 14 items, got 13"},
                      [](Json& c) { c["matrix"][2].erase(0); }},
        BadCovariance{"ExtraParameter",
                      "covariance.matrix",
                      {"expected 15 items, got 14"},
                      [](Json& c) { c["parameters"].push_back("k3"); }},
        BadCovariance{"UnknownIntrinsicSuggestsTheNearest",
                      "covariance.parameters[1]",
                      {"unknown parameter \"fyy\"", "did you mean \"fy\"?",
                       "(known: fx, fy, cx, cy, s, k1, k2, p1, p2, k3 for this lens model, camera_from_world.rx … tz "
                       "or views[i].camera_from_board.rx … tz)"},
                      [](Json& c) { c["parameters"][1] = "fyy"; }},
        BadCovariance{"UnknownPoseAxis",
                      "covariance.parameters[8]",
                      {"unknown parameter \"camera_from_world.qx\"", "did you mean \"camera_from_world.rx\"?"},
                      [](Json& c) { c["parameters"][8] = "camera_from_world.qx"; }},
        BadCovariance{"MalformedViewIndex",
                      "covariance.parameters[8]",
                      {"unknown parameter \"views[one].camera_from_board.rx\"", "; use fx, fy, cx, cy",
                       "or views[i].camera_from_board.rx … tz"},
                      [](Json& c) { c["parameters"][8] = "views[one].camera_from_board.rx"; }},
        BadCovariance{"DuplicateParameter",
                      "covariance.parameters[1]",
                      {"duplicate parameter \"fx\"", "list each parameter once"},
                      [](Json& c) { c["parameters"][1] = "fx"; }},
        BadCovariance{"NoParameters",
                      "covariance.parameters",
                      {"no parameters"},
                      [](Json& c) {
                        c["parameters"] = Json::array();
                        c["matrix"] = Json::array();
                      }},
        BadCovariance{"EntryNotANumber",
                      "covariance.matrix[4][5]",
                      {"expected a number, got the string \"0\""},
                      [](Json& c) { c["matrix"][4][5] = "0"; }},
        BadCovariance{"NotPositiveSemiDefinite",
                      "covariance.matrix",
                      {"not positive semi-definite: eigenvalue -", "< -1e-9 × largest |eigenvalue|",
                       "; write a covariance matrix (correlations within [-1, 1], no negative eigenvalue)"},
                      [](Json& c) {  // a correlation of 2 between fx and fy
                        const double r = 2 * std::sqrt(c["matrix"][0][0].get<double>() * c["matrix"][1][1].get<double>());
                        c["matrix"][0][1] = r;
                        c["matrix"][1][0] = r;
                      }},
        BadCovariance{"ViewTangentWithoutViews",
                      "covariance.parameters[8]",
                      {"\"views[0].camera_from_board.rx\" names view 0, but the file has no views",
                       "; add the views or drop the parameter"},
                      [](Json& c) { c["parameters"][8] = "views[0].camera_from_board.rx"; }},
        BadCovariance{"ViewIndexBeyondTheViews",
                      "covariance.parameters[9]",
                      {"\"views[2].camera_from_board.ry\" names view 2, but the file has 2 views",
                       "; use views[0] … views[1] or drop the parameter"},
                      [](Json& c) { c["parameters"][9] = "views[2].camera_from_board.ry"; },
                      [](Json& camera) {
                        for (const char* name : {"a", "b"}) {
                          camera["views"].push_back({{"name", name}, {"camera_from_board", camera["camera_from_world"]}});
                        }
                      }},
        BadCovariance{"WorldTangentWithoutThePose",
                      "covariance.parameters[8]",
                      {"\"camera_from_world.rx\" is a tangent of camera_from_world, which the file does not have",
                       "; add \"camera_from_world\" or drop the parameter"},
                      [](Json&) {},
                      [](Json& camera) {
                        camera.erase("camera_from_world");
                        camera.erase("P");
                      }},
        // A planar-views camera's pose blocks (docs/formats.md#camera-covariance): its covariance
        // names fx, fy, cx, cy, k1, k2, p1, p2 and has 8 pose blocks.
        BadCovariance{"UnknownPose",
                      "covariance.poses[0].pose",
                      {"unknown pose \"views[0].camera\"", "name camera_from_world or views[i].camera_from_board"},
                      [](Json& c) { c["poses"][0]["pose"] = "views[0].camera"; },
                      [](Json&) {}, true},
        BadCovariance{"PoseBeyondTheViews",
                      "covariance.poses[1].pose",
                      {"\"views[8].camera_from_board\" names view 8, but the file has 8 views",
                       "use views[0] … views[7] or drop the parameter"},
                      [](Json& c) { c["poses"][1]["pose"] = "views[8].camera_from_board"; },
                      [](Json&) {}, true},
        BadCovariance{"WorldPoseWithoutCameraFromWorld",
                      "covariance.poses[2].pose",
                      {"is a tangent of camera_from_world, which the file does not have"},
                      [](Json& c) { c["poses"][2]["pose"] = "camera_from_world"; },
                      [](Json&) {}, true},
        BadCovariance{"DuplicatePose",
                      "covariance.poses[3].pose",
                      {"duplicate pose \"views[0].camera_from_board\"", "give each pose one block"},
                      [](Json& c) { c["poses"][3]["pose"] = "views[0].camera_from_board"; },
                      [](Json&) {}, true},
        BadCovariance{"PoseBlockNotSymmetric",
                      "covariance.poses[0].matrix[1][0]",
                      {"differs from matrix[0][1]: not symmetric"},
                      [](Json& c) {
                        Json& m = c["poses"][0]["matrix"];
                        m[1][0] = 2 * m[0][1].get<double>() + 1;
                      },
                      [](Json&) {}, true},
        BadCovariance{"PoseBlockNegativeVariance",
                      "covariance.poses[0].matrix[4][4]",
                      {"the variance of \"views[0].camera_from_board.ty\" is negative"},
                      [](Json& c) { c["poses"][0]["matrix"][4][4] = -1.0; },
                      [](Json&) {}, true},
        BadCovariance{"PoseBlockShortCrossRow",
                      "covariance.poses[5].with_parameters[2]",
                      {"expected 8 items, got 7"},
                      [](Json& c) { c["poses"][5]["with_parameters"][2].erase(0); },
                      [](Json&) {}, true},
        BadCovariance{"PoseBlockCrossCovarianceTooLarge",
                      "covariance.poses[6]",
                      {"with the parameters, not positive semi-definite"},
                      [](Json& c) { c["poses"][6]["with_parameters"][0][0] = 1e3; },
                      [](Json&) {}, true},
        BadCovariance{"PoseBlockMissingMatrix",
                      "covariance.poses[7].matrix",
                      {"missing field", "add \"matrix\""},
                      [](Json& c) { c["poses"][7].erase("matrix"); },
                      [](Json&) {}, true}),
    [](const auto& param_info) { return param_info.param.name; });

}  // namespace
}  // namespace vstcal::cli_test
