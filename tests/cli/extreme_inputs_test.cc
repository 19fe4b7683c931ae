// Valid but extreme inputs through every tool (docs/reliability.md#extreme-inputs): a generator,
// seeded and deterministic, draws scenes with every lens model, poses from head-on to 75° tilt and
// rolled upside down, focal lengths from fisheye-wide to telephoto, pixel noise from 0 to 30 px,
// points moved onto the image's edge, and chains whose error σ's range from 1e-9 to 1e3. Every tool
// must answer each with a documented outcome: exit 0 and readable, finite outputs, or exit 2 / 3
// with one line and no output. A crash, a sanitizer report (the suite also runs under ASan+UBSan),
// exit 1 (an internal error, e.g. a non-finite number on its way to a file) or a partial output
// fails the test.
#include <cmath>
#include <iostream>

#include "cli_fixture.h"
#include "vstcal/random/philox.h"

namespace vstcal::cli_test {
namespace {

class CliExtremeInputs : public CliTest {
 protected:
  // Runs a tool and checks the outcome contract; `outputs` are the files a success must leave.
  // Returns true on exit 0.
  bool Check(std::string_view tool, const std::vector<std::string>& args, const std::vector<std::string>& outputs,
             const std::string& scenario) {
    const CommandResult r = Run(tool, args);
    std::string command(tool);
    for (const std::string& a : args) command += " " + a;
    EXPECT_TRUE(r.exit_code == kOk || r.exit_code == kBadInput || r.exit_code == kDegenerate)
        << scenario << ": " << command << "\nexit " << r.exit_code << "\n" << r.err;
    if (r.exit_code != kOk) {
      std::cout << scenario << ": " << command << "\n  → " << r.err;  // refusals are fine: said for the record
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << scenario << ": " << command << "\n" << r.err;
      EXPECT_EQ(r.err.rfind(std::string(tool) + ": error: ", 0), 0u) << scenario << ": " << r.err;
      for (const std::string& o : outputs) EXPECT_FALSE(fs::exists(Path(o))) << scenario << ": " << o << " left behind";
      return false;
    }
    for (const std::string& o : outputs) {
      EXPECT_TRUE(fs::exists(Path(o))) << scenario << ": " << command << " wrote no " << o;
      if (o.ends_with(".json") && fs::exists(Path(o))) {
        EXPECT_NO_THROW(ReadJson(o)) << o;
      }
    }
    return true;
  }

  void Clear() {
    for (const auto& entry : fs::directory_iterator(Path("out"))) fs::remove_all(entry.path());
  }
};

// The calibration pipeline on drawn scenes, then every format and tool the camera can go through.
TEST_F(CliExtremeInputs, EveryToolAnswersEveryDrawnScene) {
  const CounterRng rng(20240607, 0);
  const std::vector<std::string> distortions = {"", "-0.45,0.2,0.002,-0.003,-0.05",
                                                "0.9,-0.2,1e-3,-1e-3,0.05,1.2,-0.4,0.1", "1e-12,0,0,0,1e-12"};
  int scenes = 0, solved_cameras = 0, edge_points = 0;
  for (int k = 0; k < 6; ++k) {
    const auto a = rng.Uniform2(static_cast<uint64_t>(k), 0), b = rng.Uniform2(static_cast<uint64_t>(k), 1),
               c = rng.Uniform2(static_cast<uint64_t>(k), 2);
    const bool planar = k % 2 == 1;
    const int width = k == 4 ? 64 : 1280, height = k == 4 ? 48 : 720;
    std::vector<std::string> synth = {"--image-size", std::to_string(width) + "x" + std::to_string(height),
                                      "--hfov-deg", std::to_string(10 + 150 * a[0]),
                                      "--noise", k == 2 ? "30" : k == 3 ? "0" : std::to_string(0.01 + a[1]),
                                      "--seed", std::to_string(k), "--grid", planar ? "9x6" : "15x11",
                                      "--skew-deg", k == 5 ? "89.5" : "90"};
    if (const std::string& d = distortions[static_cast<size_t>(k) % distortions.size()]; !d.empty()) {
      synth.insert(synth.end(), {"--distortion", d});
    }
    if (planar) {
      synth.insert(synth.end(), {"--rig", "planar-views", "--views", "8", "--max-tilt-deg", std::to_string(75 * b[0]),
                                 "--spacing", "30", "--distance", std::to_string(200 + 2000 * b[1])});
    } else {
      synth.insert(synth.end(), {"--tilt-deg", std::to_string(75 * b[0]), "--roll-deg", std::to_string(360 * b[1]),
                                 "--tilt-direction-deg", std::to_string(360 * c[0]), "--camera-distance",
                                 std::to_string(300 + 5000 * c[1]), "--no-test-points", "--spacing", "100",
                                 "--near", "0", "--far", "400", "--interval", "200"});
    }
    const std::string scenario = "scenario " + std::to_string(k);
    Clear();
    synth.insert(synth.end(), {"-o", "out/scene.json"});
    if (!Check("calib-synth", synth, {"out/scene.json", "out/scene.truth.json"}, scenario)) continue;
    ++scenes;
    fs::rename(Path("out/scene.json"), Path("in/scene.json"));
    fs::rename(Path("out/scene.truth.json"), Path("in/scene.truth.json"));

    // Every pixel within 2 px of the image's border moved exactly onto it (u = −0.5 or W − 0.5,
    // v likewise): the extreme values the reader accepts, within the noise of the geometry.
    Json scene = ReadJson("in/scene.json");
    int on_edge = 0;
    for (Json& view : scene["views"]) {
      for (Json& p : view["points"]) {
        for (const auto& [column, size] : {std::pair<int, int>{3, width}, {4, height}}) {
          const double x = p[column].get<double>();
          if (x < 1.5) p[column] = -0.5, ++on_edge;
          if (x > size - 2.5) p[column] = size - 0.5, ++on_edge;
        }
      }
    }
    WriteJson("in/edge.json", scene);
    edge_points += on_edge;

    const std::vector<std::string> uncertainty = {"--uncertainty-grid", "1000", "--grid-size", "4x3",
                                                  "--uncertainty-pixel", "0,0,500", "--loss", "huber"};
    std::vector<std::string> tsai = {"in/edge.json", "-o", "out/cam.json", "--residuals", "out/res.json",
                                     "--distortion", "k1,k2,p1,p2,k3"};
    tsai.insert(tsai.end(), uncertainty.begin(), uncertainty.end());
    const bool solved = Check("calib-tsai", tsai, {"out/cam.json", "out/res.json"}, scenario);
    if (!planar) {
      std::vector<std::string> dlt = {"in/edge.json", "-o", "out/dlt.json", "--refine", "--solver", "svd"};
      dlt.insert(dlt.end(), uncertainty.begin(), uncertainty.end());
      Check("calib-dlt", dlt, {"out/dlt.json"}, scenario);
    }
    if (!solved) continue;
    ++solved_cameras;
    fs::rename(Path("out/cam.json"), Path("in/cam.json"));
    Check("calib-compare", {"in/scene.truth.json", "in/cam.json"}, {}, scenario);
    for (const std::string ext : {"yaml", "cameramodel"}) {
      std::vector<std::string> convert = {"in/cam.json", "-o", "out/cam." + ext};
      if (ext == "cameramodel") convert.insert(convert.end(), {"--length-unit", "m"});
      if (Check("calib-convert", convert, {"out/cam." + ext}, scenario)) {
        Check("calib-convert", {"out/cam." + ext, "-o", "out/back-" + ext + ".json"}, {"out/back-" + ext + ".json"},
              scenario);
      }
    }

    // A chain through the solved camera and its covariance, σ's from 1e-9 to 1e3.
    const double sigma = std::pow(10.0, -9 + 12 * c[0]);
    auto normal = [](double s) { return Json{{"distribution", "normal"}, {"sigma", s}}; };
    auto pose = [](double tx, double ty, double tz) { return Json{{"rotvec_deg", {0, 0, 0}}, {"t", {tx, ty, tz}}}; };
    Json chain = {{"format", "vstcal/vst-chain@1"}, {"length_unit", "mm"}, {"samples", 64}, {"seed", k}};
    chain["frames"] = {{"tracker_from_world", pose(0, 0, 0)},
                       {"hmd_from_tracker", pose(0, 0, 2000)},
                       {"camera_from_hmd", {{"left", pose(31.5, 0, 0)}, {"right", pose(-31.5, 0, 0)}}},
                       {"world_from_object", pose(0, 0, 0)}};
    // Left: the solved camera and its covariance; right: the truth, with the scene's own lens model.
    chain["cameras"] = {{"left", {{"file", "cam.json"}}}, {"right", {{"file", "scene.truth.json"}}}};
    chain["display"] = {{"ipd", 63.0}};
    chain["test_points"] = {{{"name", "centre"}, {"world", {0, 0, 0}}, {"surface_behind", 1e-6}}};
    chain["sources"] = {{"tracking", {{"rotation_deg", normal(sigma)}, {"translation", normal(sigma)}}},
                        {"camera_intrinsic", {{"left", {{"covariance", "camera"}}}}},
                        {"rendering", {{"disparity_px", normal(1e3 * sigma)}}},
                        {"display", {{"ipd", normal(sigma)}}}};
    WriteJson("in/chain.json", chain);
    Check("err-sim", {"run", "in/chain.json", "-o", "out/run.json", "--budget-samples", "32", "-q"}, {"out/run.json"},
          scenario);
    Check("err-sim", {"sweep", "in/chain.json", "-o", "out/sweep.json", "--points", "3", "-q"}, {"out/sweep.json"},
          scenario);
    Check("err-sim", {"linear", "in/chain.json", "-o", "out/linear.json", "-q"}, {"out/linear.json"}, scenario);
    Check("err-sim", {"sobol", "in/chain.json", "-o", "out/sobol.json", "--samples", "32", "--bootstrap", "10", "-q"},
          {"out/sobol.json"}, scenario);
  }
  // Extreme, not impossible: most drawn scenes must go all the way through, or the test says little.
  EXPECT_EQ(scenes, 6);
  EXPECT_GE(solved_cameras, 4);
  EXPECT_GT(edge_points, 0);
}

}  // namespace
}  // namespace vstcal::cli_test
