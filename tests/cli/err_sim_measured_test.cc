// CLI test of err-sim on a measured chain (issue 22 item 3, issue 21 item 4): calib-synth records a
// headset moving in front of a board, calib-handeye solves it and estimates the tracker's noise
// from a static log, and err-sim runs a chain that references both files — its budget says, per
// source and term, which distribution was measured (and from which file) and which was assumed, in
// the text, the JSON report and the page.
#include <cmath>
#include <cstdio>
#include <random>

#include <fstream>
#include <sstream>

#include "cli_fixture.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal::cli_test {
namespace {

using CliErrSimMeasured = CliTest;

Json PoseJson(const Rigid3d& p) {
  Json R = Json::array();
  for (int r = 0; r < 3; ++r) R.push_back({p.R(r, 0), p.R(r, 1), p.R(r, 2)});
  return {{"R", R}, {"t", {p.t.x(), p.t.y(), p.t.z()}}};
}

Rigid3d PoseOf(const Json& j) {
  Rigid3d p;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p.R(r, c) = j.at("R")[r][c].get<double>();
  for (int i = 0; i < 3; ++i) p.t(i) = j.at("t")[i].get<double>();
  return p;
}

// A static tracker log (TUM, metres): 0.02° and 0.1 mm per axis of noise about one pose.
std::string StaticLog() {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> g(0, 1);
  std::string tum;
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3d w = Eigen::Vector3d(g(rng), g(rng), g(rng)) * (0.02 * M_PI / 180);
    const Eigen::Matrix3d R = RotationFromRotvec(w);
    const auto q = QuaternionWxyzFromRotation(R);
    char line[300];
    std::snprintf(line, sizeof line, "%.6f %.9f %.9f %.9f %.12f %.12f %.12f %.12f\n", 0.005 * k, 0.5 + 1e-4 * g(rng), 1e-4 * g(rng),
                  1.2 + 1e-4 * g(rng), q[1], q[2], q[3], q[0]);
    tum += line;
  }
  return tum;
}

TEST_F(CliErrSimMeasured, BudgetSaysWhatWasMeasured) {
  ASSERT_EQ(Run("calib-synth", {"--rig", "handeye", "--image-size", "640x480", "--fx", "600", "--grid", "9x6", "--spacing", "30", "--noise",
                                "0.2", "-o", "in/rec.json"})
                .exit_code,
            kOk);
  const CommandResult solve =
      Run("calib-handeye", {"solve", "in/rec.json", "--poses", "in/rec.poses.txt", "--camera", "in/rec.truth.json", "-o", "in/he.json"});
  ASSERT_EQ(solve.exit_code, kOk) << solve.err;
  WriteText("in/still.txt", StaticLog());
  const CommandResult noise = Run("calib-handeye", {"noise", "--poses", "in/still.txt", "--from", "0", "--to", "4.9", "-o", "in/noise.json"});
  ASSERT_EQ(noise.exit_code, kOk) << noise.err;

  // The head 600 mm in front of the board's centre, looking at it: hmd_from_tracker = X ·
  // camera_from_board · Z⁻¹ with the measured X and Z; the right camera 63 mm to the right.
  const Json he = ReadJson("in/he.json");
  const Rigid3d x = PoseOf(he.at("hmd_from_camera")), z = PoseOf(he.at("tracker_from_board"));
  const Rigid3d camera_from_board{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-120, -75, 600)};
  const Rigid3d right{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-63, 0, 0)};
  Json chain;
  chain["format"] = "vstcal/vst-chain@1";
  chain["length_unit"] = "mm";
  chain["samples"] = 2000;
  chain["seed"] = 3;
  chain["handeye"] = {{"file", "he.json"}};
  chain["tracker_noise"] = {{"file", "noise.json"}};
  chain["frames"] = {{"hmd_from_tracker", PoseJson(x * camera_from_board * z.inverse())},
                     {"camera_from_hmd", {{"right", PoseJson(right * x.inverse())}}},
                     {"world_from_object", PoseJson(Rigid3d())}};
  chain["cameras"] = {{"left", {{"file", "rec.truth.json"}}}, {"right", {{"file", "rec.truth.json"}}}};
  chain["display"] = {{"ipd", 63.0}};
  chain["head_motion"] = {{"angular_velocity_deg_s", {0, 30, 0}}};
  chain["test_points"] = {{{"name", "board-centre"}, {"world", {120, 75, 0}}},
                          {{"name", "board-corner"}, {"world", {0, 0, 0}}},
                          {{"name", "in-front"}, {"world", {200, 150, -100}}}};
  chain["sources"] = {{"tracker_alignment", {{"covariance", "handeye"}}},
                      {"tracking", {{"rotation_deg", "tracker_noise"}, {"translation", "tracker_noise"}, {"latency_s", "handeye"}}},
                      {"camera_extrinsic", {{"rig", {{"covariance", "handeye"}}}}},
                      {"camera_intrinsic", {{"both", {{"fx", {{"distribution", "normal"}, {"sigma", 1.0}}}}}}}};
  WriteJson("in/chain.json", chain);

  const CommandResult r = Run("err-sim", {"run", "in/chain.json", "-o", "out/report.json", "--html", "out/report.html"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.err.find("where the distributions come from"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("    tracker_alignment: measured (he.json), "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("    camera_extrinsic: measured (he.json), "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("    camera_intrinsic: assumed, "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("; rotation: measured (noise.json); translation: measured (noise.json); latency: measured (he.json)"), std::string::npos)
      << r.err;

  const Json report = ReadJson("out/report.json");
  EXPECT_EQ(report.at("format"), "vstcal/err-sim-report@3");
  for (const Json& e : report.at("budget").at("entries")) {
    const std::string source = e.at("source");
    const Json& origin = e.at("origin");
    if (source == "camera_extrinsic") {
      EXPECT_EQ(e.at("terms")[0].at("term"), "camera_extrinsic.rig.pose");  // the mount's six modes, one term
    }
    if (source == "camera_intrinsic") {
      EXPECT_EQ(origin, Json::parse(R"([{"kind": "assumed"}])"));
    } else {
      ASSERT_GE(origin.size(), 1u) << source;
      EXPECT_EQ(origin[0].at("kind"), "measured") << source;
      EXPECT_EQ(origin[0].at("format"), source == "tracking" ? "vstcal/tracker-noise@1" : "vstcal/handeye@1") << source;
    }
  }
  // The list of origins follows the default ranking (what the user sees), as the first table does.
  std::vector<std::string> listed;
  const size_t list = r.err.find("where the distributions come from");
  ASSERT_NE(list, std::string::npos);
  std::istringstream lines(r.err.substr(r.err.find('\n', list) + 1));
  for (std::string line; std::getline(lines, line) && line.rfind("    ", 0) == 0;) {
    listed.push_back(line.substr(4, line.find(':') - 4));
  }
  EXPECT_EQ(Json(listed), report.at("budget").at("ranking").at("image"));
  // err-sim check reads the report with its new fields, as it reads older ones.
  const CommandResult check = Run("err-sim", {"check", "out/report.json", "--report", "out/report.json"});
  EXPECT_EQ(check.exit_code, kOk) << check.err;

  const std::string page = ReadText("out/report.html");
  EXPECT_NE(page.find("measured (<span title=\"vstcal/handeye@1\">he.json</span>)"), std::string::npos);
  EXPECT_NE(page.find("<td class=\"origin\" style=\"text-align:left\">assumed</td>"), std::string::npos);

  // A measurement that doubts itself (calib-handeye's warnings, e.g. views locked midway between the
  // tracker's reports): err-sim repeats its warnings after the budget's provenance. Warnings that are
  // not a list of strings are refused, naming the file and field.
  EXPECT_FALSE(r.err.find("the measurement files warn") != std::string::npos) << r.err;
  Json doubted = he;
  doubted["warnings"] = {"the time offset's σ is about 17 % too small"};
  WriteJson("in/he.json", doubted);
  const CommandResult warned = Run("err-sim", {"run", "in/chain.json", "-o", "out/report2.json"});
  ASSERT_EQ(warned.exit_code, kOk) << warned.err;
  EXPECT_NE(warned.err.find("  the measurement files warn (their σ's are used as written):\n"
                            "    he.json: the time offset's σ is about 17 % too small\n"),
            std::string::npos)
      << warned.err;
  doubted["warnings"] = {1, 2};
  WriteJson("in/he.json", doubted);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/report3.json"}), "err-sim", kBadInput, "he.json", {"warnings"}));
  EXPECT_FALSE(fs::exists(Path("out/report3.json")));
}

}  // namespace
}  // namespace vstcal::cli_test

namespace vstcal::cli_test {
namespace {

using CliErrSimFisheye = CliTest;

Json ShippedJson(const std::string& relative) {
  std::ifstream in(std::string(VSTCAL_SOURCE_DIR) + "/" + relative);
  return Json::parse(in);
}

// err-sim on a Kannala–Brandt (fisheye) camera (issue 23 item 3). Its coefficients are tan's series,
// θd = θ(1 + θ²/3 + 2θ⁴/15 + 17θ⁶/315 + 62θ⁸/2835) = tan θ − O(θ¹¹), so the fisheye camera projects as
// the pinhole with the same K to about 1e-5 px at the chain's angles (< 35° off axis): the
// error-free chain's systematic misperception (projection and unprojection only) must agree to that,
// and each test point's mean image error within the two runs' Monte Carlo standard errors (their θ
// vectors differ by the four coefficients, so their samples are not the same draws).
TEST_F(CliErrSimFisheye, TanSeriesFisheyeCameraRunsAsItsPinhole) {
  Json pinhole = ShippedJson("datasets/zedmini/clean.truth.json");
  ASSERT_EQ(pinhole.at("distortion").at("model"), "none");
  Json fisheye = pinhole;
  fisheye["distortion"] = {{"model", "kannala-brandt"}, {"k1", 1.0 / 3}, {"k2", 2.0 / 15}, {"k3", 17.0 / 315}, {"k4", 62.0 / 2835}};
  WriteJson("in/pinhole.json", pinhole);
  WriteJson("in/fisheye.json", fisheye);
  Json chain = ShippedJson("datasets/vst/seed001.json");
  for (const char* camera : {"pinhole", "fisheye"}) {
    chain["cameras"] = {{"left", {{"file", std::string(camera) + ".json"}}}, {"right", {{"file", std::string(camera) + ".json"}}}};
    WriteJson(std::string("in/") + camera + "-chain.json", chain);
    const CommandResult r = Run("err-sim", {"run", std::string("in/") + camera + "-chain.json", "--samples", "4000", "--no-budget",
                                            "-o", std::string("out/") + camera + ".json", "-q"});
    ASSERT_EQ(r.exit_code, kOk) << r.err;
  }
  const Json a = ReadJson("out/pinhole.json"), b = ReadJson("out/fisheye.json");
  const double systematic_a = a.at("totals").at("systematic_misperception_rms").get<double>();
  const double systematic_b = b.at("totals").at("systematic_misperception_rms").get<double>();
  EXPECT_NEAR(systematic_b, systematic_a, 1e-4 * systematic_a);
  ASSERT_EQ(a.at("test_points").size(), b.at("test_points").size());
  for (size_t k = 0; k < a.at("test_points").size(); ++k) {
    for (const char* eye : {"left", "right"}) {
      const Json& sa = a.at("test_points")[k].at("image").at(eye).at("pixel_px");
      const Json& sb = b.at("test_points")[k].at("image").at(eye).at("pixel_px");
      const double se = std::hypot(sa.at("mean_standard_error").get<double>(), sb.at("mean_standard_error").get<double>());
      EXPECT_NEAR(sb.at("mean").get<double>(), sa.at("mean").get<double>(), 4 * se) << "test point " << k << ", " << eye;
    }
  }
}

}  // namespace
}  // namespace vstcal::cli_test
