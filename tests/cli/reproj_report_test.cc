// CLI tests of reproj-report: the report agrees with the solver's own fit (another code path), the
// normalized residuals of a refined camera are consistent with its covariance, several cameras
// side by side, points behind the camera marked, and every bad input refused with one line, exit
// code 2 and no report left behind (issue 13 item 8).
#include <algorithm>
#include <cmath>
#include <map>

#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

class CliReprojReport : public CliTest {
 protected:
  // The default volume with 0.5 px noise and seed 000's five test points, and calib-dlt's refined
  // camera from it (in/cam.json).
  void SolveNoisyVolume() {
    Synth("in/volume.json", Override(Remove(DefaultSynthArgs(), "--no-test-points", false), "--noise", "0.5"));
    const CommandResult r = Run("calib-dlt", {"in/volume.json", "--refine", "-o", "in/cam.json", "-q"});
    ASSERT_EQ(r.exit_code, kOk) << r.err;
  }
};

TEST_F(CliReprojReport, AgreesWithTheSolversOwnFit) {
  SolveNoisyVolume();
  const CommandResult r = Run("reproj-report", {"in/cam.json", "in/volume.json", "-o", "out/report.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_TRUE(r.out.empty());
  const Json report = ReadJson("out/report.json"), cam = ReadJson("in/cam.json");
  EXPECT_EQ(report["format"], "vstcal/reproj-report@1");
  const Json& c = report["cameras"][0];
  // calib-dlt's fit block comes from scene/fit.cc, not from the report module.
  EXPECT_EQ(c["overall"]["error_px"]["n"], cam["fit"]["n_points"]);
  EXPECT_NEAR(c["overall"]["error_px"]["rms"].get<double>(), cam["fit"]["rms_px"].get<double>(), 1e-12);
  EXPECT_NEAR(c["overall"]["error_px"]["max"].get<double>(), cam["fit"]["max_px"].get<double>(), 1e-12);
  for (size_t v = 0; v < 3; ++v) {
    EXPECT_NEAR(c["views"][v]["error_px"]["rms"].get<double>(), cam["fit"]["views"][v]["rms_px"].get<double>(), 1e-12);
  }
  ASSERT_EQ(c["test_points"]["points"].size(), 5u);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(c["test_points"]["points"][i]["error_px"].get<double>(),
                cam["fit"]["test_points"][i]["error_px"].get<double>(), 1e-12);
  }
  // Refined with a covariance: the residuals are as large as it says (docs/math/report-statistics.md#normalized).
  EXPECT_NEAR(c["normalized"]["chi2_per_dof"].get<double>(), 1.0, 0.15);
  EXPECT_EQ(report["volume"]["hull"], "ok");
  EXPECT_EQ(report["grid"]["cols"].get<int>() * report["grid"]["rows"].get<int>(), static_cast<int>(c["grid"].size()));
  // Every lens parameter with the camera file's value and the square root of its covariance's
  // diagonal; the held skew has no σ.
  const Json& K = cam["K"];
  const std::map<std::string, double> shown_in_k = {{"fx", K[0][0]}, {"fy", K[1][1]}, {"cx", K[0][2]}, {"cy", K[1][2]}, {"s", K[0][1]}};
  const Json& names = cam["covariance"]["parameters"];
  ASSERT_EQ(c["parameters"].size(), 10u);  // radial-tangential: fx fy cx cy s k1 k2 p1 p2 k3
  for (const Json& p : c["parameters"]) {
    const std::string name = p["name"];
    const double expected = shown_in_k.count(name) ? shown_in_k.at(name) : cam["distortion"][name].get<double>();
    EXPECT_EQ(p["value"].get<double>(), expected) << name;
    const auto it = std::find(names.begin(), names.end(), Json(name));
    if (it == names.end()) {
      EXPECT_TRUE(p["sigma"].is_null()) << name;
      continue;
    }
    const size_t k = static_cast<size_t>(it - names.begin());
    EXPECT_EQ(p["sigma"].get<double>(), std::sqrt(cam["covariance"]["matrix"][k][k].get<double>())) << name;
  }
}

// An unrefined DLT camera has a covariance (docs/math/dlt.md#covariance) and its σ̂ in
// dlt.uncertainty: the report normalizes its residuals and gives its projection uncertainty.
TEST_F(CliReprojReport, DltCameraHasProjectionUncertainty) {
  Synth("in/volume.json", Override(Override(Remove(DefaultSynthArgs(), "--no-test-points", false), "--noise", "0.5"),
                                   "--distortion", "0,0,0,0,0"));
  ASSERT_EQ(Run("calib-dlt", {"in/volume.json", "-o", "in/cam.json", "-q"}).exit_code, kOk);
  const CommandResult r = Run("reproj-report", {"in/cam.json", "in/volume.json", "-o", "out/report.json", "--grid", "4x3"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(r.err.find("has no covariance"), std::string::npos) << r.err;
  const Json report = ReadJson("out/report.json");
  const Json& c = report["cameras"][0];
  EXPECT_EQ(c["method"], "dlt");
  EXPECT_TRUE(c["normalized"]["chi2_per_dof"].is_number()) << c["normalized"].dump();
  EXPECT_NEAR(c["normalized"]["chi2_per_dof"].get<double>(), 1.0, 0.15);
  ASSERT_EQ(c["projection_uncertainty"]["sigma_major_px"].size(), 12u);
  for (const Json& s : c["projection_uncertainty"]["sigma_major_px"]) {
    if (s.is_number()) {
      EXPECT_GT(s.get<double>(), 0);
    }
  }
}

TEST_F(CliReprojReport, CamerasSideBySideAndATable) {
  SolveNoisyVolume();
  const CommandResult r = Run("reproj-report", {"in/cam.json", "in/volume.truth.json", "in/volume.json", "-o",
                                                "out/report.json", "--format", "text", "--grid", "4x3"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json report = ReadJson("out/report.json");
  ASSERT_EQ(report["cameras"].size(), 2u);
  EXPECT_EQ(report["cameras"][1]["method"], "synthetic");
  EXPECT_FALSE(report["cameras"][1]["normalized"]["chi2_per_dof"].is_number());  // the truth has no covariance
  EXPECT_TRUE(report["cameras"][1]["projection_uncertainty"].is_null());
  EXPECT_EQ(report["cameras"][0]["projection_uncertainty"]["sigma_major_px"].size(), 12u);
  ASSERT_EQ(report["differences"].size(), 1u);
  EXPECT_EQ(report["differences"][0]["camera"], 1);
  EXPECT_EQ(report["cameras"][0]["grid"].size(), 12u);
  EXPECT_NE(r.out.find("camera 1: in/volume.truth.json (synthetic)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("camera 1 vs camera 0:"), std::string::npos) << r.out;
}

TEST_F(CliReprojReport, PointsBehindTheCameraAreMarkedNotCounted) {
  SolveNoisyVolume();
  Json corr = ReadJson("in/volume.json");
  const Pinhole truth = Pinhole::FromTruth(ReadJson("in/volume.truth.json"));
  const Eigen::Vector3d behind = truth.Centre() - 200 * truth.R.row(2).transpose();
  corr["views"][0]["points"].push_back({behind.x(), behind.y(), behind.z(), 320.0, 240.0});
  WriteJson("in/behind.json", corr);
  const CommandResult r = Run("reproj-report", {"in/cam.json", "in/behind.json", "-o", "out/report.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json c = ReadJson("out/report.json")["cameras"][0];
  EXPECT_EQ(c["excluded"]["behind_camera"], 1);
  EXPECT_EQ(c["overall"]["error_px"]["n"], 60);  // of 61
  const Json& view = c["views"][0];
  EXPECT_EQ(view["excluded"][0]["index"], 20);
  EXPECT_EQ(view["excluded"][0]["reason"], "behind-camera");
  EXPECT_TRUE(view["points"][20][2].is_null());
  // Said on stderr too (issue 24: exit 0 and nothing said).
  EXPECT_EQ(r.err, "reproj-report: note: in/cam.json: 1 of 61 points left out of the statistics: 1 behind the camera\n");
}

TEST_F(CliReprojReport, PlanarViewsAndAViewTheCameraHasNoPoseFor) {
  Synth("in/views.json", {"--image-size", "640x480", "--fx", "600", "--rig", "planar-views", "--views", "4", "--grid",
                          "8x6", "--spacing", "30", "--noise", "0.2"});
  Json corr = ReadJson("in/views.json");
  corr["views"][2]["name"] = "renamed";  // the truth camera has poses for view-00 … view-03 only
  WriteJson("in/renamed.json", corr);
  const CommandResult r = Run("reproj-report", {"in/views.truth.json", "in/renamed.json", "-o", "out/report.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json report = ReadJson("out/report.json");
  EXPECT_EQ(report["volume"]["hull"], "planar views: the boards share no world frame");
  const Json& c = report["cameras"][0];
  EXPECT_EQ(c["excluded"]["no_pose"], 48);
  EXPECT_EQ(c["overall"]["error_px"]["n"], 3 * 48);
  EXPECT_TRUE(c["views"][2]["error_px"].is_null());
  EXPECT_EQ(c["views"][2]["excluded"].size(), 48u);
  EXPECT_EQ(c["views"][2]["excluded"][0]["reason"], "no-pose");
  EXPECT_EQ(c["views"][1]["error_px"]["n"], 48);
  EXPECT_EQ(r.err, "reproj-report: note: in/views.truth.json: 48 of 192 points left out of the statistics: 48 in views the "
                   "camera has no pose for (renamed: its solver dropped them)\n");
}

TEST_F(CliReprojReport, OnePlaneSpansNoVolume) {
  // One plane of points: no hull, so no test point is called inside or outside.
  Synth("in/plane.json", Override(Override(Remove(DefaultSynthArgs(), "--no-test-points", false), "--far", "0"),
                                  "--noise", "0.2"));
  const CommandResult r = Run("reproj-report", {"in/plane.truth.json", "in/plane.json", "-o", "out/report.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json report = ReadJson("out/report.json");
  EXPECT_EQ(report["volume"]["hull"], "the points lie on one plane: they span no volume");
  const Json& tests = report["cameras"][0]["test_points"];
  EXPECT_TRUE(tests["inside"]["error_px"].is_null());
  EXPECT_TRUE(tests["outside"]["error_px"].is_null());
  for (const Json& t : tests["points"]) EXPECT_TRUE(t["inside_volume"].is_null());
  // The camera file (calib-synth's truth) follows the same rule with the same words.
  const Json truth = ReadJson("in/plane.truth.json");
  EXPECT_EQ(truth["fit"]["volume"]["hull"], report["volume"]["hull"]);
  ASSERT_EQ(truth["fit"]["test_points"].size(), tests["points"].size());
  for (const Json& t : truth["fit"]["test_points"]) EXPECT_TRUE(t["inside_volume"].is_null()) << t["name"];
}

TEST_F(CliReprojReport, DifferentImageSize) {
  SolveNoisyVolume();
  Synth("in/other.json", Override(DefaultSynthArgs(), "--image-size", "800x600"));
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/other.truth.json", "in/volume.json", "-o", "out/report.json"}),
                        "reproj-report", kBadInput, "in/other.truth.json: image_size: ",
                        {"800x600 differs from in/volume.json's 640x480", "images of that size"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliReprojReport, DifferentLengthUnit) {
  SolveNoisyVolume();
  Json cam = ReadJson("in/cam.json");
  cam["length_unit"] = "m";
  WriteJson("in/metres.json", cam);
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/metres.json", "in/volume.json", "-o", "out/report.json"}),
                        "reproj-report", kBadInput, "in/metres.json: length_unit: ",
                        {"\"m\" differs from in/volume.json's \"mm\"", "calib-convert"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliReprojReport, VolumeCameraWithoutAPose) {
  SolveNoisyVolume();
  Json cam = ReadJson("in/volume.truth.json");
  cam.erase("camera_from_world");
  cam.erase("P");
  cam.erase("fit");
  WriteJson("in/nopose.json", cam);
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/nopose.json", "in/volume.json", "-o", "out/report.json"}),
                        "reproj-report", kBadInput, "in/nopose.json: camera_from_world: ", {"missing", "volume rig"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliReprojReport, EmptyView) {
  SolveNoisyVolume();
  Json corr = ReadJson("in/volume.json");
  corr["views"][1]["points"] = Json::array();
  WriteJson("in/empty.json", corr);
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/cam.json", "in/empty.json", "-o", "out/report.json"}), "reproj-report",
                        kBadInput, "in/empty.json: views[1].points", {}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliReprojReport, ReportInAMissingFolder) {
  SolveNoisyVolume();
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/cam.json", "in/volume.json", "-o", "out/nope/report.json"}),
                        "reproj-report", kBadInput, "out/nope/report.json", {}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliReprojReport, ReportOverAnInput) {
  SolveNoisyVolume();
  const std::string before = ReadText("in/volume.json");
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/cam.json", "in/volume.json", "-o", "in/volume.json"}),
                        "reproj-report", kBadInput, "in/volume.json", {}));
  EXPECT_EQ(ReadText("in/volume.json"), before);
}

TEST_F(CliReprojReport, CamerasAndCorrespondencesInTheWrongOrder) {
  SolveNoisyVolume();
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/volume.json", "in/cam.json", "-o", "out/report.json"}),
                        "reproj-report", kBadInput, "in/volume.json: format: ", {"vstcal/camera@1"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliReprojReport, BadUsage) {
  SolveNoisyVolume();
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/volume.json", "-o", "out/report.json"}), "reproj-report", kBadInput,
                        "", {}));
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/cam.json", "in/volume.json", "-o", "out/r.json", "--grid", "0x3"}),
                        "reproj-report", kBadInput, "--grid", {}));
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/cam.json", "in/volume.json", "-o", "out/r.json", "--grid", "1000x1000"}),
                        "reproj-report", kBadInput, "--grid", {}));
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/cam.json", "in/volume.json", "-o", "out/r.json", "--format", "xml"}),
                        "reproj-report", kBadInput, "--format", {}));
  EXPECT_TRUE(OutDirEmpty());
}

}  // namespace
}  // namespace vstcal::cli_test
