// CLI tests of reproj-report with a stereo rig (RIG LEFT RIGHT): a rig calib-stereo solved from
// calib-synth's noise-free views of a volume triangulates every point where it is (zero error, all
// 315 points of the 9 × 7 grid on five planes) and splits the test points inside and outside the
// calibration points' hull; a point one camera missed is left out and counted;
// views are matched by name or by --match-views' key;
// the page renders offline in Chromium with the JSON's numbers; every bad input is refused with one
// line, exit code 2 and nothing written.
#include <cmath>
#include <tuple>

#include <opencv2/imgcodecs.hpp>

#include "browser_fixture.h"

namespace vstcal::cli_test {
namespace {

class CliReprojReportStereo : public BrowserTest {
 protected:
  // in/l.json, in/r.json: the volume of calib_stereo_test's volume rig (two 1280×720 cameras 1.2 m
  // away, converging by 1.5° each side, baseline ≈ 73 mm) with `noise` px (and seed 000's five test
  // points), and in/rig.json solved from them.
  void SolveVolumeRig(const std::string& noise = "0", bool test_points = false) {
    for (const auto& [eye, direction, seed] : {std::tuple{"l", "180", "1"}, std::tuple{"r", "0", "2"}}) {
      std::vector<std::string> args = {"--image-size", "1280x720", "--fx", "700", "--distortion", "-0.1,0.02,0,0,0",
                                       "--grid", "9x7", "--spacing", "80", "--near", "0", "--far", "400", "--interval", "100",
                                       "--camera-distance", "1200", "--tilt-deg", "1.5", "--tilt-direction-deg", direction,
                                       "--noise", noise, "--seed", seed, "--camera-name", eye};
      if (!test_points) args.push_back("--no-test-points");
      Synth(std::string("in/") + eye + ".json", args);
    }
    const CommandResult r = Run("calib-stereo", {"solve", "in/l.json", "in/r.json", "-o", "in/rig.json"});
    ASSERT_EQ(r.exit_code, kOk) << r.err;
  }

  ::testing::AssertionResult Refused(const std::vector<std::string>& args, const std::string& location,
                                     const std::vector<std::string>& phrases) {
    auto result = FailsWith(Run("reproj-report", args), "reproj-report", kBadInput, location, phrases);
    if (!result) return result;
    return OutDirEmpty();
  }
};

TEST_F(CliReprojReportStereo, NoiseFreeRigTriangulatesEveryPointWhereItIs) {
  SolveVolumeRig("0", true);
  const CommandResult r =
      Run("reproj-report", {"in/rig.json", "in/l.json", "in/r.json", "-o", "out/report.json", "--format", "text"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.out.find("5 views seen by both cameras"), std::string::npos) << r.out;
  const Json report = ReadJson("out/report.json");
  EXPECT_EQ(report["format"], "vstcal/reproj-report@1");
  const Json& s = report["stereo"];
  EXPECT_EQ(s["target"], "volume");
  EXPECT_EQ(s["length_unit"], "mm");
  EXPECT_EQ(s["overall"]["linear"]["n"], 9 * 7 * 5);
  for (const char* measure : {"x", "y", "z", "linear", "lateral", "depth"}) {
    EXPECT_LT(s["overall"][measure]["max"].get<double>(), 1e-6) << measure;  // mm at 1.2 m
  }
  ASSERT_EQ(s["views"].size(), 5u);
  EXPECT_EQ(s["views"][0]["left_pose"], "ok");
  EXPECT_EQ(s["views"][0]["points"][0].size(), 10u);
  EXPECT_EQ(s["excluded"]["left_only"], 0);
  // The test points, never used in the solve, matched by name.
  ASSERT_EQ(s["test_points"]["points"].size(), 5u);
  for (const Json& t : s["test_points"]["points"]) EXPECT_TRUE(t["excluded"].is_null()) << t["name"];
  EXPECT_EQ(s["test_points"]["stats"]["linear"]["n"], 5);
  EXPECT_LT(s["test_points"]["stats"]["linear"]["max"].get<double>(), 1e-6);
  // Split by the hull of the calibration points, the box of the 9 × 7 grid at 80 mm (x within
  // ±320 mm) on planes z = 0 … 400 mm: seed 000's "Left" (x = −760) and "Right" (x = 480) lie
  // beyond its sides, the three "Middle" points inside.
  EXPECT_EQ(s["volume"]["hull"], "ok");
  EXPECT_EQ(s["volume"]["vertices"], 8);
  for (const Json& t : s["test_points"]["points"]) {
    EXPECT_EQ(t["inside_volume"].get<bool>(), t["name"].get<std::string>().starts_with("Middle")) << t["name"];
  }
  EXPECT_EQ(s["test_points"]["inside"]["linear"]["n"], 3);
  EXPECT_EQ(s["test_points"]["outside"]["linear"]["n"], 2);
  // Each camera's reprojection error per image cell (--grid, default 8 × 6): noise-free, none.
  EXPECT_EQ(s["grid"], Json({{"cols", 8}, {"rows", 6}}));
  for (const char* eye : {"left", "right"}) {
    const Json& cells = s["reprojection"][eye]["grid"];
    ASSERT_EQ(cells.size(), 48u);
    int n = 0;
    for (const Json& c : cells) {
      if (c["error_px"].is_null()) continue;
      n += c["error_px"]["n"].get<int>();
      EXPECT_LT(c["error_px"]["max"].get<double>(), 1e-6) << eye;
    }
    EXPECT_EQ(n, 9 * 7 * 5) << eye;
    EXPECT_EQ(s["reprojection"][eye]["error_px"]["n"], 9 * 7 * 5) << eye;
    // Per view: each camera's 63 points reprojected through the rig, none off.
    for (const Json& v : s["views"]) {
      const Json& view = v["reprojection"][eye];
      EXPECT_EQ(view["error_px"]["n"], 9 * 7) << eye;
      EXPECT_LT(view["error_px"]["max"].get<double>(), 1e-6) << eye;
      ASSERT_EQ(view["points"].size(), 63u);
      EXPECT_EQ(view["points"][0].size(), 4u);
      EXPECT_TRUE(view["excluded"].empty());
    }
    EXPECT_NE(r.out.find("view " + s["views"][4]["name"].get<std::string>() + " " + eye + " px"), std::string::npos) << r.out;
  }

  // A test point the right camera did not measure: listed, not measured.
  Json right = ReadJson("in/r.json");
  right["test_points"][1].erase("pixel");
  WriteJson("in/r-unmeasured.json", right);
  ASSERT_EQ(Run("reproj-report", {"in/rig.json", "in/l.json", "in/r-unmeasured.json", "-o", "out/t.json"}).exit_code, kOk);
  const Json t = ReadJson("out/t.json")["stereo"]["test_points"];
  EXPECT_EQ(t["points"][1]["excluded"], "left-only");
  EXPECT_TRUE(t["points"][1]["error"][0].is_null());
  EXPECT_EQ(t["stats"]["linear"]["n"], 4);
}

TEST_F(CliReprojReportStereo, APointOneCameraMissedIsCountedNotMeasured) {
  SolveVolumeRig();
  Json right = ReadJson("in/r.json");
  right["views"][0]["points"].erase(3);
  WriteJson("in/r-missing.json", right);
  const CommandResult r = Run("reproj-report", {"in/rig.json", "in/l.json", "in/r-missing.json", "-o", "out/report.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json s = ReadJson("out/report.json")["stereo"];
  EXPECT_EQ(s["excluded"]["left_only"], 1);
  EXPECT_EQ(s["overall"]["linear"]["n"], 9 * 7 * 5 - 1);
  EXPECT_EQ(s["views"][0]["excluded"][0]["index"], 3);
  EXPECT_EQ(s["views"][0]["excluded"][0]["reason"], "left-only");
  EXPECT_TRUE(s["views"][0]["points"][3][3].is_null());
}

TEST_F(CliReprojReportStereo, ViewsMatchedByAKeyPattern) {
  SolveVolumeRig();
  Json right = ReadJson("in/r.json");
  for (Json& v : right["views"]) v["name"] = "right-" + v["name"].get<std::string>();
  WriteJson("in/r-named.json", right);
  const CommandResult r = Run("reproj-report", {"in/rig.json", "in/l.json", "in/r-named.json", "-o", "out/report.json",
                                                "--match-views", "(plane-[0-9]+)$"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json s = ReadJson("out/report.json")["stereo"];
  EXPECT_EQ(s["overall"]["linear"]["n"], 9 * 7 * 5);
  EXPECT_EQ(s["views"][0]["name"], "plane-00");
  fs::remove(Path("out/report.json"));  // the failures below must leave out/ empty
  EXPECT_TRUE(Refused({"in/rig.json", "in/l.json", "in/r-named.json", "-o", "out/report.json", "--match-views", "plane"},
                      "--match-views: ", {"has no group"}));
  EXPECT_TRUE(Refused({"in/rig.json", "in/l.json", "in/r-named.json", "-o", "out/report.json", "--match-views", "(x[0-9])"},
                      "in/l.json: views: ", {"does not match --match-views"}));
  EXPECT_TRUE(Refused({"in/l.json", "in/l.json", "-o", "out/report.json", "--match-views", "([0-9]+)$"},
                      "--match-views: ", {"goes with a stereo rig"}));
}

// The page as a person sees it: rendered by headless Chromium with no console message, its three
// charts decoded (error against depth, each camera's heat map over a --grid of 4 × 3 cells), every number shown equal to the JSON's, a screenshot kept; and the same bytes twice.
TEST_F(CliReprojReportStereo, PageRendersOfflineWithTheJsonsNumbers) {
  ASSERT_TRUE(fs::exists(kChromium)) << "scripts/setup installs chromium";
  SolveVolumeRig("0.3", true);
  const std::vector<std::string> args = {"in/rig.json", "in/l.json", "in/r.json", "-o", "out/report.json", "--html", "out/report.html",
                                         "--grid", "4x3"};
  ASSERT_EQ(Run("reproj-report", args).exit_code, kOk);
  const PageView view = View("out/report.html", "reproj-report-stereo.png", 1000, 1400);
  const std::string& dom = view.dom;
  // Error against depth; each camera's heat map and residual overlay.
  EXPECT_EQ(ExpectInlinePictures(dom), 5u);
  const Json report = ReadJson("out/report.json");
  const Json& tests = report["stereo"]["test_points"];
  ASSERT_EQ(tests["points"].size(), 5u);
  // Overall 7 rows of 6 statistics; per view the left and right reprojection RMS, the points
  // triangulated, the linear RMS and max; 7 rows inside and 7 outside the volume (those of a side
  // without a point are dashes); each test point's dx, dy, dz and linear.
  const size_t sides = !tests["inside"]["linear"].is_null() + !tests["outside"]["linear"].is_null();
  EXPECT_EQ(ExpectNumbersOf(report, dom), 7u * 6u + 5u * 5u + sides * 7u * 6u + 5u * 4u);
  EXPECT_EQ(Attributes(dom, "data-key").size(), 7u * 6u + 5u * 5u + sides * 7u * 6u + 5u * 4u);
  size_t inside_cells = 0, reprojection_cells = 0;
  for (const std::string& key : Attributes(dom, "data-key")) {
    inside_cells += key.starts_with("/stereo/test_points/inside/");
    reprojection_cells += key.starts_with("/stereo/views/") && key.ends_with("/error_px/rms");
  }
  EXPECT_EQ(inside_cells, tests["inside"]["linear"].is_null() ? 0u : 7u * 6u);
  EXPECT_EQ(reprojection_cells, 5u * 2u);  // both cameras of every view
  // 0.3 px of noise per coordinate: every view's reprojection RMS of either camera near √2 · 0.3.
  for (const Json& v : report["stereo"]["views"]) {
    for (const char* eye : {"left", "right"}) {
      EXPECT_NEAR(v["reprojection"][eye]["error_px"]["rms"].get<double>(), 0.3 * std::sqrt(2.0), 0.1) << eye;
    }
  }
  // Each camera's overlay draws the 315 points of the five views (no image named: a blank canvas).
  const std::string page = ReadText("out/report.html");
  const auto count = [](const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  const std::string blank = "all views on a blank canvas (the correspondences name no image); 315 residuals drawn";
  EXPECT_EQ(count(page, "The left camera's residual vectors against its own PnP pose: " + blank), 1u);
  EXPECT_EQ(count(page, "The right camera's residual vectors through the rig's relative pose: " + blank), 1u);
  EXPECT_EQ(view.images, "5 loaded, 0 broken");
  EXPECT_EQ(report["stereo"]["reprojection"]["right"]["grid"].size(), 12u);
  EXPECT_EQ(view.wide_tables, "none");
  EXPECT_TRUE(SameBytesTwice("reproj-report", args, {"out/report.json", "out/report.html"}));

  // The right file names view 2's image: the right overlay is drawn on it (through the rig), the
  // left one still on a blank canvas (the same PNG encoding the browser decoded above, so Chromium
  // is not started again); a named image that is missing is refused naming its field.
  Json right = ReadJson("in/r.json");
  const std::string view2 = right["views"][2]["name"];
  right["views"][2]["image"] = "views/r2.png";
  WriteJson("in/r-named.json", right);
  fs::create_directories(Path("in/views"));
  ASSERT_TRUE(cv::imwrite(Path("in/views/r2.png").string(), cv::Mat(720, 1280, CV_8UC1, cv::Scalar(90))));
  const CommandResult named = Run("reproj-report", {"in/rig.json", "in/l.json", "in/r-named.json", "-o", "out/named.json", "--html", "out/named.html"});
  ASSERT_EQ(named.exit_code, kOk) << named.err;
  const std::string named_page = ReadText("out/named.html");
  EXPECT_EQ(count(named_page, "The right camera's residual vectors through the rig's relative pose: view " + view2 +
                                 " on its image views/r2.png; 63 residuals drawn"), 1u);
  EXPECT_EQ(count(named_page, "The left camera's residual vectors against its own PnP pose: " + blank), 1u);
  right["views"][2]["image"] = "views/missing.png";
  WriteJson("in/r-missing.json", right);
  fs::remove_all(Path("out"));
  fs::create_directories(Path("out"));
  EXPECT_TRUE(Refused({"in/rig.json", "in/l.json", "in/r-missing.json", "-o", "out/m.json", "--html", "out/m.html"},
                      "in/r-missing.json: views[2].image: ", {"not found", "blank canvas"}));
}

TEST_F(CliReprojReportStereo, BadInput) {
  SolveVolumeRig();
  Json right = ReadJson("in/r.json");
  Json other = right;
  other["image_size"] = {1920, 1080};
  WriteJson("in/r-size.json", other);
  EXPECT_TRUE(Refused({"in/rig.json", "in/l.json", "in/r-size.json", "-o", "out/report.json"}, "in/r-size.json: image_size: ",
                      {"1920x1080 differs from in/rig.json's right camera (1280x720)"}));
  other = right;
  other["length_unit"] = "m";
  WriteJson("in/r-m.json", other);
  EXPECT_TRUE(Refused({"in/rig.json", "in/l.json", "in/r-m.json", "-o", "out/report.json"}, "in/r-m.json: length_unit: ",
                      {"\"m\" differs from in/rig.json's \"mm\"", "calib-convert"}));
  other = right;
  for (Json& v : other["views"]) v["name"] = v["name"].get<std::string>() + "-right";
  WriteJson("in/r-renamed.json", other);
  EXPECT_TRUE(Refused({"in/rig.json", "in/l.json", "in/r-renamed.json", "-o", "out/report.json"},
                      "in/l.json and in/r-renamed.json: views: ", {"no view name is in both files", "matched by name"}));
  EXPECT_TRUE(Refused({"in/rig.json", "in/l.json", "-o", "out/report.json"}, "in/rig.json: ",
                      {"two correspondences files after it, LEFT then RIGHT; got 1"}));
  EXPECT_TRUE(Refused({"in/rig.json", "in/l.json", "in/r.json", "-o", "out/nope/report.json"}, "out/nope/report.json: ",
                      {"does not exist"}));
  EXPECT_TRUE(Refused({"in/rig.json", "in/l.json", "in/r.json", "-o", "out/report.json", "--grid", "0x3"}, "--grid: ", {}));
}

}  // namespace
}  // namespace vstcal::cli_test
