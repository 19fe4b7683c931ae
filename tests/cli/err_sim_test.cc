// CLI tests of err-sim: bad chains and flags get exit code 2 and one line naming the file, the field
// and the fix (with a did-you-mean for unknown keys), and no output file; sizes beyond their
// documented maximum and conflicting flags are refused; a chain whose every sample of a test point
// is undefined exits 3; any lens model runs; good runs are reproducible for any thread count and
// shard split; a normalised chain is a fixed point.
#include <cmath>
#include <cstring>
#include <map>

#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

using CliErrSim = CliTest;

Json Normal(double sigma) { return {{"distribution", "normal"}, {"sigma", sigma}}; }

Json Pose(double rx, double ry, double rz, double tx, double ty, double tz) {
  return {{"rotvec_deg", {rx, ry, rz}}, {"t", {tx, ty, tz}}};
}

// A small chain: inline 640×480 pinhole cameras 63 mm apart, the hmd 1 m in front of the world
// origin, three test points, every source active with small errors.
Json SmallChain() {
  const Json camera = {{"image_size", {640, 480}},
                       {"K", {{500.0, 0.0, 319.5}, {0.0, 500.0, 239.5}, {0.0, 0.0, 1.0}}},
                       {"distortion", {{"model", "none"}}}};
  Json c;
  c["format"] = "vstcal/vst-chain@1";
  c["length_unit"] = "mm";
  c["samples"] = 3000;
  c["seed"] = 7;
  c["frames"] = {{"tracker_from_world", Pose(0, 0, 0, 100, -200, 500)},
                 {"hmd_from_tracker", Pose(0, 0, 0, -100, 200, 500)},
                 {"camera_from_hmd", {{"left", Pose(0, 0, 0, 31.5, 0, 0)}, {"right", Pose(0, 0, 0, -31.5, 0, 0)}}},
                 {"world_from_object", Pose(0, 0, 0, 0, 0, 0)}};
  c["cameras"] = {{"left", camera}, {"right", camera}};
  c["display"] = {{"ipd", 63.0}};
  c["head_motion"] = {{"angular_velocity_deg_s", {0, 20, 0}}};
  c["test_points"] = {{{"name", "a"}, {"world", {0, 0, 0}}, {"surface_behind", 20.0}},
                      {{"name", "b"}, {"world", {100, -50, 200}}},
                      {{"name", "c"}, {"world", {-150, 80, -300}}}};
  c["sources"] = {
      {"tracker_alignment", {{"rotation_deg", Normal(0.2)}, {"translation", Normal(2.0)}}},
      {"tracking", {{"translation", Normal(1.0)}, {"latency_s", {{"distribution", "uniform"}, {"min", 0.0}, {"max", 0.03}}}}},
      {"camera_extrinsic", {{"rig", {{"rotation_deg", Normal(0.1)}}}, {"baseline", Normal(0.1)}}},
      {"camera_intrinsic", {{"both", {{"fx", Normal(1.0)}, {"cx", Normal(1.0)}}}}},
      {"rendering", {{"disparity_px", Normal(0.5)}}},
      {"display", {{"ipd", {{"distribution", "fixed"}, {"value", 2.0}}}, {"both", {{"eyepoint", Normal(1.0)}}}}},
      {"virtual_object_alignment", {{"fiducials", {{0, 0, 0}, {200, 0, 0}, {0, 200, 0}, {0, 0, 200}}}, {"fle_rms", 0.5}}}};
  return c;
}

Json WithoutProvenance(Json j) {
  j.erase("provenance");
  return j;
}

TEST_F(CliErrSim, RunWritesTheReport) {
  WriteJson("in/chain.json", SmallChain());
  const CommandResult r = Run("err-sim", {"run", "in/chain.json", "-o", "out/report.json", "--budget-samples", "1000"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("error budget"), std::string::npos) << r.err;
  const Json report = ReadJson("out/report.json");
  EXPECT_EQ(report["format"], "vstcal/err-sim-report@3");
  EXPECT_EQ(report["samples"], 3000);
  // Shares of the whole: every measure's sources and its remainder row add to 1, in the file and
  // in the text.
  for (const char* measure : {"image", "misregistration"}) {
    double total = report["budget"]["whole"][measure]["remainder_share"].get<double>();
    for (const Json& e : report["budget"]["entries"]) total += e["share_of_" + std::string(measure) + "_ms"].get<double>();
    EXPECT_NEAR(total, 1.0, 1e-12) << measure;
  }
  EXPECT_NE(r.err.find("interactions and means in common"), std::string::npos) << r.err;
  const size_t whole = r.err.find("       whole chain ");
  ASSERT_NE(whole, std::string::npos) << r.err;
  EXPECT_NE(r.err.substr(whole, r.err.find('\n', whole) - whole).find("100.0 %  100.0 %"), std::string::npos) << r.err;
  // The tree source → term: tracking's latency and translation alone, the advice naming the
  // dominant term, each term in the JSON with its shares.
  for (const Json& e : report["budget"]["entries"]) {
    ASSERT_FALSE(e["terms"].empty()) << e["source"];
    if (e["source"] == "tracking") {
      ASSERT_EQ(e["terms"].size(), 2u);
      EXPECT_EQ(e["terms"][0]["term"], "tracking.translation");
      EXPECT_EQ(e["terms"][1]["term"], "tracking.latency");
      EXPECT_TRUE(e["terms"][1]["share_of_image_ms"].is_number());
    }
  }
  EXPECT_NE(r.err.find("         tracking.latency"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("→ mostly "), std::string::npos) << r.err;
  EXPECT_EQ(report["test_points"].size(), 3u);
  EXPECT_EQ(report["budget"]["entries"].size(), 7u);
  EXPECT_EQ(report["budget"]["ranking"]["misregistration"].size(), 7u);
  EXPECT_EQ(report["budget"]["ranking"]["misperception"].size(), 7u);
  EXPECT_EQ(report["budget"]["ranking"]["misperception"][0], "display");
  // The default ranking is by what the user sees (issue 21 item 3): the image misregistration's
  // share, largest first, in the file and in the text, which says so; the 3-D rank beside it.
  EXPECT_EQ(report["budget"]["ranked_by"], "image");
  ASSERT_EQ(report["budget"]["ranking"]["image"].size(), 7u);
  double previous = 2;
  for (const Json& source : report["budget"]["ranking"]["image"]) {
    for (const Json& e : report["budget"]["entries"]) {
      if (e["source"] != source) continue;
      EXPECT_LE(e["share_of_image_ms"].get<double>(), previous) << source;
      previous = e["share_of_image_ms"].get<double>();
      EXPECT_TRUE(e["dominant_term"]["image"].is_string()) << source;
    }
  }
  const size_t first = r.err.find("error budget of what the user sees");
  ASSERT_NE(first, std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ranked by each source's share of the whole chain's mean square of the image misregistration; the 3-D "
                       "misregistration's share and rank beside it:", first),
            std::string::npos)
      << r.err;
  const std::string top = report["budget"]["ranking"]["image"][0].get<std::string>();
  EXPECT_NE(r.err.find("    1  " + top, first), std::string::npos) << r.err;
  EXPECT_LT(first, r.err.find("error budget of the misperception")) << r.err;
  EXPECT_TRUE(report["test_points"][0]["occlusion"].is_object());
  EXPECT_TRUE(report["test_points"][1]["occlusion"].is_null());
  EXPECT_EQ(report["test_points"][1]["undefined"]["samples"], 0);
  EXPECT_TRUE(report["test_points"][1]["misregistration"]["linear"]["p95"].is_number());
  EXPECT_TRUE(report["test_points"][1]["misperception"]["systematic"]["offset"].is_array());
  EXPECT_EQ(report["provenance"]["tool"], "err-sim");
  EXPECT_EQ(report["provenance"]["seed"], 7);  // from the chain file: the seed the run used
  for (const Json& e : report["budget"]["entries"]) {
    if (e["source"] == "display") {
      // Display errors move the overlay and the video together (to rounding), not where things seem.
      EXPECT_LT(e["alone"]["image_rms_px"].get<double>(), 1e-9);
      EXPECT_LT(e["alone"]["misregistration_rms"].get<double>(), 1e-9);
      EXPECT_GT(e["alone"]["misperception_rms"].get<double>(), 0.1);
    }
  }
}

TEST_F(CliErrSim, SameBitsForAnyThreadCountAndShardSplit) {
  WriteJson("in/chain.json", SmallChain());
  const std::vector<std::string> base = {"run", "in/chain.json", "--samples", "2500", "--budget-samples", "700", "-q"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  ASSERT_EQ(Run("err-sim", with({"-o", "out/t1.json", "--threads", "1"})).exit_code, kOk);
  ASSERT_EQ(Run("err-sim", with({"-o", "out/t2.json", "--threads", "2"})).exit_code, kOk);
  EXPECT_EQ(WithoutProvenance(ReadJson("out/t1.json")), WithoutProvenance(ReadJson("out/t2.json")));
  for (const std::string i : {"0", "1", "2"}) {
    ASSERT_EQ(Run("err-sim", with({"-o", "out/s" + i + ".json", "--shard", i + "/3"})).exit_code, kOk);
    EXPECT_EQ(ReadJson("out/s" + i + ".json")["format"], "vstcal/err-sim-shard@2");
  }
  const CommandResult m = Run("err-sim", {"merge", "in/chain.json", "out/s2.json", "out/s0.json", "out/s1.json", "-o", "out/m.json", "-q"});
  ASSERT_EQ(m.exit_code, kOk) << m.err;
  Json merged = WithoutProvenance(ReadJson("out/m.json")), single = WithoutProvenance(ReadJson("out/t1.json"));
  EXPECT_EQ(merged, single);
}

TEST_F(CliErrSim, OnlyAndWithoutSelectSources) {
  WriteJson("in/chain.json", SmallChain());
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--only", "display", "--no-budget", "-q"}).exit_code, kOk);
  const Json only = ReadJson("out/r.json");
  EXPECT_EQ(only["sources"]["active"], Json::array({"display"}));
  EXPECT_LT(only["totals"]["image_rms_px"].get<double>(), 1e-9);
  EXPECT_TRUE(only["budget"].is_null());
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "out/w.json", "--without", "display,tracking", "--no-budget", "-q"}).exit_code, kOk);
  EXPECT_EQ(ReadJson("out/w.json")["sources"]["active"].size(), 5u);
}

TEST_F(CliErrSim, UnknownSourceKeySuggestsTheClosest) {
  Json c = SmallChain();
  c["sources"]["trackin"] = c["sources"]["tracking"];
  c["sources"].erase("tracking");
  WriteJson("in/chain.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/chain.json: sources.trackin: ", {"unknown error source \"trackin\"", "did you mean \"tracking\"?"}));
  EXPECT_TRUE(OutDirEmpty());
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--only", "dispaly"}), "err-sim", kBadInput,
                        "--only: ", {"unknown error source \"dispaly\"", "did you mean \"display\"?"}));
}

TEST_F(CliErrSim, UnknownTermAndDistribution) {
  Json c = SmallChain();
  c["sources"]["tracking"]["latency"] = Normal(0.01);
  WriteJson("in/term.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/term.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/term.json: sources.tracking.latency: ", {"unknown term of tracking", "did you mean \"latency_s\"?"}));
  c = SmallChain();
  c["sources"]["tracking"]["translation"]["distribution"] = "gaussian";
  WriteJson("in/dist.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/dist.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/dist.json: sources.tracking.translation.distribution: ", {"unknown distribution \"gaussian\"", "normal"}));
  EXPECT_TRUE(OutDirEmpty());
}

// A display that is not the camera (issue 21 item 5): a field of view 1.25 × the camera's tangent
// magnifies the shown video, and the report's systematic misperception is the closed form's — the
// eyes (on the cameras here) see each point at depth Z/1.25, its lateral position kept
// (docs/math/vst-chain.md#display-fov). A field of 0° or 180° or more is no field: exit 2, one line
// naming it, nothing written.
TEST_F(CliErrSim, ADisplayFieldOfViewIsPartOfTheSystematicMisperception) {
  Json c = SmallChain();
  const double m = 1.25;
  c["display"]["field_of_view_deg"] = 2 * std::atan(m * 320.0 / 500.0) * 180 / M_PI;
  WriteJson("in/chain.json", c);
  const CommandResult r = Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--no-budget", "--samples", "200", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json report = ReadJson("out/r.json");
  for (size_t k = 0; k < 3; ++k) {
    const Json& world = report["test_points"][k]["world"];
    const double depth = world[2].get<double>() + 1000;  // the hmd frame: 1 m behind the world origin
    const Json& offset = report["test_points"][k]["misperception"]["systematic"]["offset"];
    EXPECT_NEAR(offset[0].get<double>(), 0.0, 1e-9 * depth) << k;
    EXPECT_NEAR(offset[1].get<double>(), 0.0, 1e-9 * depth) << k;
    EXPECT_NEAR(offset[2].get<double>(), depth / m - depth, 1e-9 * depth) << k;
  }
  for (const double bad : {0.0, 180.0, 250.0}) {
    c["display"]["field_of_view_deg"] = bad;
    WriteJson("in/bad.json", c);
    std::filesystem::remove_all(Path("out"));
    std::filesystem::create_directories(Path("out"));
    EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/bad.json", "-o", "out/bad.json"}), "err-sim", kBadInput,
                          "in/bad.json: display.field_of_view_deg: ", {"must lie strictly between 0 and 180 degrees", "0 < φ < 180"}))
        << bad;
    EXPECT_TRUE(OutDirEmpty()) << bad;
  }
}

TEST_F(CliErrSim, NegativeSigma) {
  Json c = SmallChain();
  c["sources"]["tracker_alignment"]["rotation_deg"]["sigma"] = {0.1, -0.2, 0.1};
  WriteJson("in/chain.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/chain.json: sources.tracker_alignment.rotation_deg.sigma[1]: ",
                        {"must not be negative", "give a standard deviation ≥ 0"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliErrSim, MissingFrame) {
  Json c = SmallChain();
  c["frames"].erase("hmd_from_tracker");
  WriteJson("in/chain.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/chain.json: frames.hmd_from_tracker: ", {"missing field", "add \"hmd_from_tracker\""}));
  c = SmallChain();
  c["frames"]["hmd_form_tracker"] = c["frames"]["hmd_from_tracker"];
  WriteJson("in/typo.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/typo.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/typo.json: frames.hmd_form_tracker: ", {"did you mean \"hmd_from_tracker\"?"}));
  EXPECT_TRUE(OutDirEmpty());
}

// A camera reference that leads nowhere names the chain's field as well as the path it resolved to.
TEST_F(CliErrSim, CameraReferenceAndCountsNameTheChainsField) {
  Json c = SmallChain();
  c["cameras"]["left"] = {{"file", "nope.json"}};
  WriteJson("in/missing.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/missing.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/missing.json: cameras.left.file: ", {"names in/nope.json, which does not exist", "relative to the chain's folder"}));
  c["cameras"]["left"] = {{"file", "."}};
  WriteJson("in/dir.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/dir.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/dir.json: cameras.left.file: ", {"a directory", "give the camera@1 file's path"}));
  c = SmallChain();
  c["samples"] = 0;
  WriteJson("in/zero.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/zero.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/zero.json: samples: ", {"expected a whole number from 1 to 10^12, got 0"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliErrSim, TestPointBehindACamera) {
  Json c = SmallChain();
  c["test_points"][1]["world"] = {0, 0, -1200};  // the hmd is 1 m in front of the origin, looking at it
  WriteJson("in/chain.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/chain.json: test_points[1].world: ", {"lies behind the left camera", "move the point in front"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliErrSim, CovarianceFromTheCameraFile) {
  Json c = SmallChain();
  Json camera = c["cameras"]["left"];
  camera["format"] = "vstcal/camera@1";
  camera["length_unit"] = "mm";
  camera["method"] = "dlt";
  WriteJson("in/plain.camera.json", camera);
  // A pose tangent is ignored by err-sim; in a camera@1 file it must name a pose the file has.
  const Json covariance = {{"parameters", {"fx", "fy", "cx", "cy", "camera_from_world.rx"}},
                           {"matrix", {{1.0, 0.5, 0, 0, 0}, {0.5, 1.0, 0, 0, 0}, {0, 0, 0.25, 0, 0}, {0, 0, 0, 0.25, 0}, {0, 0, 0, 0, 1e-6}}}};
  camera["covariance"] = covariance;
  WriteJson("in/noworld.camera.json", camera);
  camera["camera_from_world"] = {{"R", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, {"t", {0, 0, 1000}}};
  WriteJson("in/cov.camera.json", camera);
  c["cameras"]["left"] = {{"file", "cov.camera.json"}};
  c["cameras"]["right"] = {{"file", "plain.camera.json"}};
  c["sources"]["camera_intrinsic"] = {{"left", {{"covariance", "camera"}}}, {"right", {{"fx", Normal(1.0)}}}};
  WriteJson("in/chain.json", c);
  const CommandResult r = Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--only", "camera_intrinsic", "--no-budget", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_GT(ReadJson("out/r.json")["totals"]["image_rms_px"].get<double>(), 0.0);

  // An inline camera has no poses: any pose tangent is accepted (and ignored).
  Json inline_chain = c;
  inline_chain["cameras"]["left"] = SmallChain()["cameras"]["left"];
  inline_chain["cameras"]["left"]["covariance"] = covariance;
  inline_chain["cameras"]["left"]["covariance"]["parameters"][4] = "views[3].camera_from_board.tz";
  WriteJson("in/inline.json", inline_chain);
  const CommandResult ri = Run("err-sim", {"run", "in/inline.json", "-o", "out/ri.json", "--only", "camera_intrinsic", "--no-budget", "-q"});
  ASSERT_EQ(ri.exit_code, kOk) << ri.err;
  EXPECT_EQ(ReadJson("out/ri.json")["totals"]["image_rms_px"], ReadJson("out/r.json")["totals"]["image_rms_px"]);

  c["cameras"]["left"] = {{"file", "noworld.camera.json"}};
  WriteJson("in/noworld.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/noworld.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/noworld.camera.json: covariance.parameters[4]: ",
                        {"\"camera_from_world.rx\" is a tangent of camera_from_world, which the file does not have",
                         "add \"camera_from_world\" or drop the parameter"}));
  c["cameras"]["left"] = {{"file", "cov.camera.json"}};

  c["sources"]["camera_intrinsic"]["right"] = {{"covariance", "camera"}};
  WriteJson("in/nocov.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/nocov.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/nocov.json: sources.camera_intrinsic.right.covariance: ", {"the right camera has no covariance"}));
}

TEST_F(CliErrSim, ShardFlagsAndMerge) {
  WriteJson("in/chain.json", SmallChain());
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--shard", "2/2"}), "err-sim", kBadInput,
                        "--shard: ", {"expected i/N with 0 ≤ i < N"}));
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "out/s0.json", "--shard", "0/2", "--no-budget", "-q"}).exit_code, kOk);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"merge", "in/chain.json", "out/s0.json", "-o", "out/m.json"}), "err-sim", kBadInput,
                        "merge: shard 1/2 is missing", {"pass every shard file"}));
  Json other = SmallChain();
  other["sources"]["tracking"]["translation"] = Normal(1.5);
  WriteJson("in/other.json", other);
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "out/s1.json", "--shard", "1/2", "--no-budget", "-q"}).exit_code, kOk);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"merge", "in/other.json", "out/s0.json", "out/s1.json", "-o", "out/m.json"}), "err-sim",
                        kBadInput, "in/other.json: is not the chain the shards ran", {"pass the same chain file"}));
  EXPECT_FALSE(fs::exists(Path("out/m.json")));
}

TEST_F(CliErrSim, SensitivitySubcommands) {
  WriteJson("in/chain.json", SmallChain());
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sweep", "in/chain.json", "-o", "out/sweep.json", "--parameter", "display.ipd"}),
                        "err-sim", kBadInput, "display.ipd", {"constant"}));  // a fixed bias has no default range
  ASSERT_EQ(Run("err-sim", {"sweep", "in/chain.json", "-o", "out/sweep.json", "--parameter", "display.ipd", "--lo", "-5", "--hi", "5", "-q"})
                .exit_code,
            kOk);
  const Json sweep = ReadJson("out/sweep.json");
  EXPECT_EQ(sweep["format"], "vstcal/err-sim-sweep@2");
  EXPECT_EQ(sweep["parameters"][0]["values"].size(), 21u);
  ASSERT_EQ(Run("err-sim", {"sobol", "in/chain.json", "-o", "out/sobol.json", "--samples", "256", "--bootstrap", "20", "-q"}).exit_code, kOk);
  EXPECT_EQ(ReadJson("out/sobol.json")["groups"].size(), 7u);
  ASSERT_EQ(Run("err-sim", {"linear", "in/chain.json", "-o", "out/linear.json", "--samples", "2000", "-q"}).exit_code, kOk);
  EXPECT_EQ(ReadJson("out/linear.json")["outputs"].size(), 30u);
  // An unknown parameter: the file, the flag, a did-you-mean (issue 8).
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sweep", "in/chain.json", "-o", "out/x.json", "--parameter", "tracking.latncy"}), "err-sim",
                        kBadInput, "in/chain.json: --parameter: ",
                        {"no parameter \"tracking.latncy\"", "did you mean \"tracking.latency\"?"}));
}

// The shipped chains (datasets/vst) read and run.
TEST_F(CliErrSim, ShippedChainsRun) {
  for (const std::string name : {"seed000", "seed001"}) {
    const std::string chain = std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/" + name + ".json";
    const CommandResult r = Run("err-sim", {"run", chain, "-o", "out/" + name + ".json", "--samples", "500", "--budget-samples", "200", "-q"});
    ASSERT_EQ(r.exit_code, kOk) << name << ": " << r.err;
    EXPECT_EQ(ReadJson("out/" + name + ".json")["undefined_samples"], 0) << name;
  }
}

// An inline camera with the rational lens model (13 parameters) crashed err-sim run (issue 8): each
// eye's lens now comes from its camera through the lens-model variant, and errors on the rational
// terms are simulated.
TEST_F(CliErrSim, RationalLensCameraRuns) {
  Json c = SmallChain();
  c["cameras"]["left"]["distortion"] = {{"model", "rational"}, {"k1", -0.05}, {"k2", 0.01}, {"p1", 0.0}, {"p2", 0.0},
                                        {"k3", 0.0}, {"k4", 0.02}, {"k5", 0.0}, {"k6", 0.0}};
  c["sources"]["camera_intrinsic"] = {{"left", {{"fx", Normal(1.0)}, {"k4", Normal(0.001)}}}, {"right", {{"k1", Normal(0.002)}}}};
  WriteJson("in/chain.json", c);
  const CommandResult r = Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--samples", "2000", "--budget-samples", "500", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json report = ReadJson("out/r.json");
  EXPECT_GT(report["totals"]["image_rms_px"].get<double>(), 0.0);
  ASSERT_EQ(Run("err-sim", {"sweep", "in/chain.json", "-o", "out/s.json", "--parameter", "camera_intrinsic.left.k4", "-q"}).exit_code, kOk);
  EXPECT_EQ(ReadJson("out/s.json")["parameters"][0]["unit"], "1");
  c["sources"]["camera_intrinsic"]["left"]["k7"] = Normal(0.1);
  WriteJson("in/k7.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/k7.json", "-o", "out/x.json"}), "err-sim", kBadInput,
                        "in/k7.json: sources.camera_intrinsic.left.k7: ", {"unknown lens parameter"}));
}

// Every size has a maximum and a one-line message beyond it; nothing is allocated first (issue 8:
// sobol --bootstrap 1e9 was killed for memory).
TEST_F(CliErrSim, SizeFlagsHaveMaximums) {
  WriteJson("in/chain.json", SmallChain());
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sobol", "in/chain.json", "-o", "out/x.json", "--bootstrap", "1000000000"}), "err-sim",
                        kBadInput, "--bootstrap: ", {"at most 10000"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sobol", "in/chain.json", "-o", "out/x.json", "--samples", "16777216"}), "err-sim",
                        kBadInput, "--samples: ", {"MiB", "at most 1 GiB"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/x.json", "--samples", "2000000000000"}), "err-sim",
                        kBadInput, "--samples: ", {"at most 10^12"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/x.json", "--budget-samples", "2000000000000"}),
                        "err-sim", kBadInput, "--budget-samples: ", {"at most 10^12"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/x.json", "--shard", "0/2000000"}), "err-sim", kBadInput,
                        "--shard: ", {"N ≤ 10^6"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/x.json", "--threads", "100000"}), "err-sim", kBadInput,
                        "--threads: ", {"at most 256"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sweep", "in/chain.json", "-o", "out/x.json", "--points", "100000"}), "err-sim", kBadInput,
                        "--points: ", {"at most 1001"}));
  Json many = SmallChain();
  for (int i = 0; i < 1001; ++i) many["test_points"].push_back({{"name", "q" + std::to_string(i)}, {"world", {0, 0, 0}}});
  WriteJson("in/many.json", many);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/many.json", "-o", "out/x.json"}), "err-sim", kBadInput,
                        "in/many.json: test_points: ", {"1004 test points", "at most 1000"}));
  // A sweep grows with the test points squared (one disparity parameter per point): 300 points at
  // the default 21 sweep points are (36 + 300) parameters × 22 × 3000 outputs (10 a point) =
  // 22,176,000 values (36: 6 tracker alignment, 4 tracking, 4 extrinsic, 4 intrinsic, 6 eyepoint,
  // 12 fiducial localisation), refused before any work.
  Json wide = SmallChain();
  for (int i = 0; i < 297; ++i) {
    wide["test_points"].push_back({{"name", "w" + std::to_string(i)}, {"world", {5.0 * (i % 20), 5.0 * (i / 20), 0.0}}});
  }
  WriteJson("in/wide.json", wide);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sweep", "in/wide.json", "-o", "out/x.json"}), "err-sim", kBadInput,
                        "in/wide.json: --points: ", {"336 parameters at 21 points", "3000 outputs", "22176000 values",
                                                     "more than the 10000000",
                                                     "--parameter"}));
  EXPECT_TRUE(OutDirEmpty());
}

// Flags that contradict each other are refused, not silently run (issue 8: --only X --without X
// ran zero sources and wrote zeros).
TEST_F(CliErrSim, ConflictingFlagsAreRefused) {
  WriteJson("in/chain.json", SmallChain());
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/x.json", "--only", "display", "--without", "display"}),
                        "err-sim", kBadInput, "--without: ", {"\"display\" is also given to --only"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/x.json", "--no-budget", "--budget-samples", "100"}),
                        "err-sim", kBadInput, "--budget-samples: ", {"--no-budget", "drop one"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/x.json", "--shard", "0/2", "--shard-count", "2"}),
                        "err-sim", kBadInput, "--shard-count: ", {"only with --shard auto"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sweep", "in/chain.json", "-o", "out/x.json", "--parameter", "display.ipd,tracking.latency",
                                         "--lo", "-1", "--hi", "1"}),
                        "err-sim", kBadInput, "--lo: ", {"exactly one --parameter"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sweep", "in/chain.json", "-o", "out/x.json", "--parameter", "display.ipd", "--lo", "2",
                                         "--hi", "1"}),
                        "err-sim", kBadInput, "--lo: ", {"not below --hi"}));
  EXPECT_TRUE(OutDirEmpty());
}

// Every sample of a test point undefined: exit code 3, one line naming the point and why, no file
// (issue 8: it printed 0.00 and exited 0). Statistics of no sample are null, never a number.
TEST_F(CliErrSim, EverySampleUndefinedExitsThree) {
  Json c = SmallChain();
  // The virtual world turned half round about the tracker: every overlay falls behind the cameras.
  c["sources"] = {{"tracker_alignment", {{"rotation_deg", {{"distribution", "fixed"}, {"value", {0, 180, 0}}}}}}};
  WriteJson("in/chain.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--samples", "100", "--no-budget"}), "err-sim",
                        kDegenerate, "in/chain.json: test point \"a\": ",
                        {"every one of the 100 samples is undefined (sample 0: behind a camera in the left eye)"}));
  EXPECT_TRUE(OutDirEmpty());
}

// A tampered shard: merge names the file and the field (issue 8: the message named no file).
TEST_F(CliErrSim, TamperedShardIsNamed) {
  WriteJson("in/chain.json", SmallChain());
  for (const std::string i : {"0", "1"}) {
    ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "out/s" + i + ".json", "--shard", i + "/2", "--samples", "3000",
                              "--no-budget", "-q"}).exit_code,
              kOk);
  }
  const Json good = ReadJson("out/s1.json");
  Json bad = good;
  bad["scenarios"][0]["summary"]["histograms"][0][0][1] = 999999;  // counts no longer match the moments
  WriteJson("in/t1.json", bad);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"merge", "in/chain.json", "out/s0.json", "in/t1.json", "-o", "out/m.json"}), "err-sim",
                        kBadInput, "in/t1.json: ", {"regenerate the shard file"}));
  bad = good;
  bad["scenarios"][0]["summary"]["nodes"][0][2][0] = {1, 2.0};
  WriteJson("in/t2.json", bad);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"merge", "in/chain.json", "out/s0.json", "in/t2.json", "-o", "out/m.json"}), "err-sim",
                        kBadInput, "in/t2.json: scenarios[0].summary.nodes[0][2][0]: ", {"expected 5 items, got 2"}));
  bad = good;
  bad["scenarios"][0]["summary"]["outputs"][0] = "renamed";
  WriteJson("in/t3.json", bad);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"merge", "in/chain.json", "out/s0.json", "in/t3.json", "-o", "out/m.json"}), "err-sim",
                        kBadInput, "in/t3.json: scenarios[0].summary: ", {"regenerate the shard file"}));
  bad = good;
  bad["only"] = {"trackng"};
  WriteJson("in/t4.json", bad);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"merge", "in/chain.json", "out/s0.json", "in/t4.json", "-o", "out/m.json"}), "err-sim",
                        kBadInput, "in/t4.json: only[0]: ", {"unknown error source"}));
  bad = good;
  bad["shard"] = {0, 2};
  WriteJson("in/t5.json", bad);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"merge", "in/chain.json", "out/s0.json", "in/t5.json", "-o", "out/m.json"}), "err-sim",
                        kBadInput, "in/t5.json: shard 0/2 is given twice", {"pass each shard once"}));
  EXPECT_FALSE(fs::exists(Path("out/m.json")));
}

// --shard auto from a Slurm array job or a Kubernetes Indexed Job: the shards merge into the
// report of one run.
TEST_F(CliErrSim, ShardAutoFromTheScheduler) {
  WriteJson("in/chain.json", SmallChain());
  const std::vector<std::string> base = {ToolPath("err-sim"), "run", "in/chain.json", "--samples", "2500", "--no-budget", "-q", "--shard", "auto"};
  auto run = [&](std::vector<std::string> env, std::vector<std::string> extra) {
    std::vector<std::string> argv = {"/usr/bin/env", "-u", "SLURM_ARRAY_TASK_ID", "-u", "JOB_COMPLETION_INDEX"};
    argv.insert(argv.end(), env.begin(), env.end());
    argv.insert(argv.end(), base.begin(), base.end());
    argv.insert(argv.end(), extra.begin(), extra.end());
    return RunCommand(argv, dir());
  };
  // Slurm: --array=1-3 gives IDs 1 … 3, shards 0 … 2.
  for (const std::string id : {"1", "2", "3"}) {
    const CommandResult r = run({"SLURM_ARRAY_TASK_ID=" + id, "SLURM_ARRAY_TASK_COUNT=3", "SLURM_ARRAY_TASK_MIN=1"},
                                {"-o", "out/slurm" + id + ".json"});
    ASSERT_EQ(r.exit_code, kOk) << r.err;
  }
  EXPECT_EQ(ReadJson("out/slurm3.json")["shard"], Json::array({2, 3}));
  // Kubernetes: the index from the Job, the count from the flag.
  for (const std::string i : {"0", "1", "2"}) {
    const CommandResult r = run({"JOB_COMPLETION_INDEX=" + i}, {"--shard-count", "3", "-o", "out/k8s" + i + ".json"});
    ASSERT_EQ(r.exit_code, kOk) << r.err;
  }
  ASSERT_EQ(Run("err-sim", {"merge", "in/chain.json", "out/slurm1.json", "out/slurm2.json", "out/slurm3.json", "-o", "out/a.json", "-q"}).exit_code, kOk);
  ASSERT_EQ(Run("err-sim", {"merge", "in/chain.json", "out/k8s0.json", "out/k8s1.json", "out/k8s2.json", "-o", "out/b.json", "-q"}).exit_code, kOk);
  EXPECT_EQ(WithoutProvenance(ReadJson("out/a.json")), WithoutProvenance(ReadJson("out/b.json")));
  EXPECT_TRUE(FailsWith(run({}, {"-o", "out/x.json"}), "err-sim", kBadInput, "--shard auto: ",
                        {"neither SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX", "--shard i/N"}));
  EXPECT_TRUE(FailsWith(run({"JOB_COMPLETION_INDEX=1"}, {"-o", "out/x.json"}), "err-sim", kBadInput, "--shard auto: ",
                        {"add --shard-count N"}));
  EXPECT_TRUE(FailsWith(run({"JOB_COMPLETION_INDEX=3"}, {"--shard-count", "3", "-o", "out/x.json"}), "err-sim", kBadInput,
                        "--shard auto: ", {"shard 3 of 3"}));
  EXPECT_TRUE(FailsWith(run({"SLURM_ARRAY_TASK_ID=x", "SLURM_ARRAY_TASK_COUNT=3"}, {"-o", "out/x.json"}), "err-sim", kBadInput,
                        "--shard auto: SLURM_ARRAY_TASK_ID is \"x\"", {"not a whole number"}));
  EXPECT_FALSE(fs::exists(Path("out/x.json")));
}

// vst-chain@1 read → write → read → write: the second pass gives the same bytes (issue 8), for a
// chain written by hand and for the shipped ones (whose camera references are rebased).
// A stereo@1 rig of SmallChain's two cameras, 63 mm apart, with a right_from_left covariance
// (σ 0.05° per rotation axis, 0.2 mm per translation axis, ty and tz correlated).
Json SmallRig() {
  Json camera = SmallChain()["cameras"]["left"];
  camera["format"] = "vstcal/camera@1";
  camera["length_unit"] = "mm";
  camera["method"] = "synthetic";
  const double w = std::pow(0.05 * 3.141592653589793 / 180, 2);
  return {{"format", "vstcal/stereo@1"},
          {"length_unit", "mm"},
          {"method", "stereo-solve"},
          {"left", camera},
          {"right", camera},
          {"right_from_left", {{"R", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, {"t", {-63.0, 0.0, 0.0}}}},
          {"baseline", 63.0},
          {"covariance",
           {{"parameters", {"right_from_left.rx", "right_from_left.ry", "right_from_left.rz", "right_from_left.tx",
                            "right_from_left.ty", "right_from_left.tz"}},
            {"matrix", {{w, 0, 0, 0, 0, 0}, {0, w, 0, 0, 0, 0}, {0, 0, w, 0, 0, 0}, {0, 0, 0, 0.04, 0, 0},
                        {0, 0, 0, 0, 0.04, 0.02}, {0, 0, 0, 0, 0.02, 0.04}}}}}};
}

// SmallChain with its cameras and right camera pose from in/rig.json, and the rig's covariance as
// the right camera's extrinsic error.
Json ChainWithRig() {
  Json c = SmallChain();
  c.erase("cameras");
  c["frames"]["camera_from_hmd"].erase("right");
  c["rig"] = {{"file", "rig.json"}};
  c["sources"]["camera_extrinsic"]["right"] = {{"covariance", "rig"}};
  return c;
}

TEST_F(CliErrSim, RigGivesTheCamerasAndTheRightCamerasError) {
  WriteJson("in/rig.json", SmallRig());
  WriteJson("in/chain.json", ChainWithRig());
  const CommandResult r = Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--only", "camera_extrinsic", "--no-budget", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_GT(ReadJson("out/r.json")["totals"]["image_rms_px"].get<double>(), 0.0);
  // Written by hand (SmallChain's cameras and frames, the covariance inline): the same run.
  Json by_hand = SmallChain();
  by_hand["sources"]["camera_extrinsic"]["right"] = {{"covariance", SmallRig()["covariance"]}};
  WriteJson("in/by_hand.json", by_hand);
  ASSERT_EQ(Run("err-sim", {"run", "in/by_hand.json", "-o", "out/h.json", "--only", "camera_extrinsic", "--no-budget", "-q"}).exit_code, kOk);
  EXPECT_EQ(ReadJson("out/r.json")["chain_digest"], ReadJson("out/h.json")["chain_digest"]);
  EXPECT_EQ(ReadJson("out/r.json")["totals"], ReadJson("out/h.json")["totals"]);

  // normalize keeps the reference (rebased onto the output's folder) and is a fixed point.
  ASSERT_EQ(Run("err-sim", {"normalize", "in/chain.json", "-o", "out/a.json", "-q"}).exit_code, kOk);
  const Json a = ReadJson("out/a.json");
  EXPECT_EQ(a["rig"], Json({{"file", "../in/rig.json"}}));
  EXPECT_FALSE(a.contains("cameras"));
  EXPECT_FALSE(a["frames"]["camera_from_hmd"].contains("right"));
  EXPECT_EQ(a["sources"]["camera_extrinsic"]["right"]["covariance"], "rig");
  ASSERT_EQ(Run("err-sim", {"normalize", "out/a.json", "-o", "out/b.json", "-q"}).exit_code, kOk);
  EXPECT_EQ(ReadText("out/a.json"), ReadText("out/b.json"));
  // The rig is an input of the run: never overwritten.
  const std::string rig_text = ReadText("in/rig.json");
  EXPECT_TRUE(FailsWith(Run("err-sim", {"normalize", "in/chain.json", "-o", "in/rig.json"}), "err-sim", kBadInput, "in/rig.json: ",
                        {"never overwrites its inputs"}));
  EXPECT_EQ(ReadText("in/rig.json"), rig_text);
}

TEST_F(CliErrSim, RigConflictsAndBadReferencesAreNamed) {
  Json rig = SmallRig();
  WriteJson("in/rig.json", rig);
  rig.erase("covariance");
  WriteJson("in/nocov.rig.json", rig);
  rig["length_unit"] = "m";
  rig["left"]["length_unit"] = "m";
  rig["right"]["length_unit"] = "m";
  rig["right_from_left"]["t"] = {-0.063, 0.0, 0.0};
  rig["baseline"] = 0.063;
  WriteJson("in/metres.rig.json", rig);
  const auto fails = [&](const Json& chain, const std::string& location, const std::vector<std::string>& phrases) {
    WriteJson("in/chain.json", chain);
    return FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json"}), "err-sim", kBadInput, location, phrases);
  };
  Json c = ChainWithRig();
  c["cameras"] = SmallChain()["cameras"];
  EXPECT_TRUE(fails(c, "in/chain.json: cameras: ", {"given with \"rig\", which holds both cameras", "delete \"cameras\""}));
  c = ChainWithRig();
  c["frames"]["camera_from_hmd"]["right"] = SmallChain()["frames"]["camera_from_hmd"]["right"];
  EXPECT_TRUE(fails(c, "in/chain.json: frames.camera_from_hmd.right: ", {"right_from_left · camera_from_hmd.left", "delete frames.camera_from_hmd.right"}));
  c = ChainWithRig();
  c["rig"]["file"] = "nope.json";
  EXPECT_TRUE(fails(c, "in/chain.json: rig.file: ", {"names in/nope.json, which does not exist", "give the stereo@1 file's path"}));
  c["rig"] = {{"path", "rig.json"}};
  EXPECT_TRUE(fails(c, "in/chain.json: rig.path: ", {"unknown field of a stereo@1 reference"}));
  c["rig"] = {{"file", "metres.rig.json"}};
  EXPECT_TRUE(fails(c, "in/chain.json: rig.file: ", {"names a rig in \"m\", but the chain is in \"mm\"", "write the chain in the rig's length unit"}));
  c["rig"] = {{"file", "nocov.rig.json"}};
  EXPECT_TRUE(fails(c, "in/chain.json: sources.camera_extrinsic.right.covariance: ", {"the rig nocov.rig.json has no covariance"}));
  c = SmallChain();
  c["sources"]["camera_extrinsic"]["right"] = {{"covariance", "rig"}};
  EXPECT_TRUE(fails(c, "in/chain.json: sources.camera_extrinsic.right.covariance: ", {"the chain references no rig", "add \"rig\""}));
  c = ChainWithRig();
  c["sources"]["camera_intrinsic"] = {{"left", {{"covariance", "camera"}}}};
  EXPECT_TRUE(fails(c, "in/chain.json: sources.camera_intrinsic.left.covariance: ",
                    {"the rig rig.json's left camera has no covariance", "calib-stereo assemble"}));
  c = ChainWithRig();
  c["sources"]["camera_extrinsic"]["right"]["covariance"] = "camera";
  EXPECT_TRUE(fails(c, "in/chain.json: sources.camera_extrinsic.right.covariance: ", {"unknown value \"camera\"", "write \"rig\""}));
  c = ChainWithRig();
  c["sources"]["camera_extrinsic"]["right"]["rotation_deg"] = Normal(0.1);
  EXPECT_TRUE(fails(c, "in/chain.json: sources.camera_extrinsic.right.rotation_deg: ", {"rotation_deg and translation do not mix with it"}));
  c = ChainWithRig();
  c["sources"]["camera_extrinsic"].erase("right");
  c["sources"]["camera_extrinsic"]["left"] = {{"covariance", "rig"}};
  EXPECT_TRUE(fails(c, "in/chain.json: sources.camera_extrinsic.left.covariance: ", {"an error of the right camera", "move it to sources.camera_extrinsic.right"}));
  c = ChainWithRig();
  c["sources"]["camera_extrinsic"]["right"]["covariance"] = {{"parameters", {"fx"}}, {"matrix", {{1.0}}}};
  EXPECT_TRUE(fails(c, "in/chain.json: sources.camera_extrinsic.right.covariance.parameters: ", {"expected 6 items, got 1"}));
  c = ChainWithRig();
  c["sources"]["camera_extrinsic"]["right"]["covariance"] = SmallRig()["covariance"];
  c["sources"]["camera_extrinsic"]["right"]["covariance"]["matrix"][3][3] = -0.04;
  EXPECT_TRUE(fails(c, "in/chain.json: sources.camera_extrinsic.right.covariance.matrix[3][3]: ",
                    {"the variance of \"right_from_left.tx\" is negative"}));
  c["sources"]["camera_extrinsic"]["right"]["covariance"]["matrix"][3][3] = 0.04;
  c["sources"]["camera_extrinsic"]["right"]["covariance"]["matrix"][4][5] = 0.1;  // |ρ| > σσ: not a covariance
  c["sources"]["camera_extrinsic"]["right"]["covariance"]["matrix"][5][4] = 0.1;
  EXPECT_TRUE(fails(c, "in/chain.json: sources.camera_extrinsic.right.covariance", {"positive semi-definite"}));
  // The rig file's own problems name the rig file.
  Json broken = SmallRig();
  broken["baseline"] = 60.0;
  WriteJson("in/rig.json", broken);
  EXPECT_TRUE(fails(ChainWithRig(), "in/rig.json: baseline: ", {"disagrees with |right_from_left.t|"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliErrSim, NormalizedChainIsAFixedPoint) {
  WriteJson("in/chain.json", SmallChain());
  std::vector<std::string> chains = {"in/chain.json"};
  for (const std::string name : {"seed000", "seed001"}) chains.push_back(std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/" + name + ".json");
  for (size_t i = 0; i < chains.size(); ++i) {
    const std::string a = "out/a" + std::to_string(i) + ".json", b = "out/b" + std::to_string(i) + ".json";
    const CommandResult first = Run("err-sim", {"normalize", chains[i], "-o", a, "-q"});
    ASSERT_EQ(first.exit_code, kOk) << first.err;
    const CommandResult second = Run("err-sim", {"normalize", a, "-o", b, "-q"});
    ASSERT_EQ(second.exit_code, kOk) << second.err;
    EXPECT_EQ(ReadText(a), ReadText(b)) << chains[i];
    // The normalised chain runs and means the same: the same digest as the original.
    ASSERT_EQ(Run("err-sim", {"run", chains[i], "-o", "out/r1.json", "--samples", "300", "--no-budget", "-q"}).exit_code, kOk);
    ASSERT_EQ(Run("err-sim", {"run", a, "-o", "out/r2.json", "--samples", "300", "--no-budget", "-q"}).exit_code, kOk);
    EXPECT_EQ(ReadJson("out/r1.json")["chain_digest"], ReadJson("out/r2.json")["chain_digest"]) << chains[i];
  }
}

// --- err-sim check ----------------------------------------------------------------------------------

// The verdict docs/tools/err-sim.md#check defines, stated here from the two reports' numbers.
std::string RiseVerdict(double accepted, double se_a, double fresh, double se_n, double allowed, double z) {
  const double excess = fresh - accepted - allowed;
  if (excess <= 0) return "pass";
  return excess <= z * std::sqrt(se_a * se_a + se_n * se_n) ? "within noise" : "fail";
}

struct ReportMetricValue {
  std::string name;
  double value, se;
};

// Every metric err-sim check compares, read from a report by this test (the means with their
// standard errors, the signed depth left out; the occlusion rates).
std::vector<ReportMetricValue> CheckedMetrics(const Json& report) {
  std::vector<ReportMetricValue> out;
  for (const Json& p : report["test_points"]) {
    const std::string n = p["name"];
    for (const char* eye : {"left", "right"}) {
      const Json& s = p["image"][eye]["pixel_px"];
      out.push_back({n + ".image." + eye + ".pixel_px", s["mean"], s["mean_standard_error"]});
    }
    for (const char* measure : {"misregistration", "misperception"}) {
      for (const char* term : {"linear", "lateral", "depth_abs", "angular_deg"}) {
        const Json& s = p[measure][term];
        out.push_back({n + "." + measure + "." + term, s["mean"], s["mean_standard_error"]});
      }
    }
    if (p["occlusion"].is_null()) continue;
    for (const char* eye : {"left", "right"}) {
      const Json& o = p["occlusion"][eye];
      out.push_back({n + ".occlusion." + eye + ".wrong_rate", o["wrong_rate"], o["standard_error"]});
    }
  }
  return out;
}

// The verdict err-sim check printed for a metric (its table row ends with it).
std::string PrintedVerdict(const std::string& out, const std::string& metric) {
  const size_t at = out.find("\n  " + metric + " ");
  if (at == std::string::npos) return "(no row)";
  const std::string row = out.substr(at + 1, out.find('\n', at + 1) - at - 1);
  for (const char* v : {"within noise", "pass", "fail"}) {
    if (row.size() >= std::strlen(v) && row.compare(row.size() - std::strlen(v), std::string::npos, v) == 0) return v;
  }
  return "(no verdict in \"" + row + "\")";
}

// Checks every printed verdict against RiseVerdict with a relative allowance; returns the counts
// of pass, within noise and fail.
std::map<std::string, int> ExpectVerdicts(const Json& accepted, const Json& fresh, const std::string& out, double fraction,
                                          double z) {
  std::map<std::string, double> value, se;
  for (const ReportMetricValue& m : CheckedMetrics(fresh)) value[m.name] = m.value, se[m.name] = m.se;
  std::map<std::string, int> counts;
  for (const ReportMetricValue& m : CheckedMetrics(accepted)) {
    const std::string expected = RiseVerdict(m.value, m.se, value.at(m.name), se.at(m.name), fraction * m.value, z);
    EXPECT_EQ(PrintedVerdict(out, m.name), expected) << m.name;
    ++counts[expected];
  }
  return counts;
}

// The accepted report against a re-run of its own chain (same samples and seed): every rise is 0.
TEST_F(CliErrSim, CheckAgainstAReRunOfItsChainPasses) {
  WriteJson("in/chain.json", SmallChain());
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "in/accepted.json", "--no-budget", "-q"}).exit_code, kOk);
  const CommandResult r = Run("err-sim", {"check", "in/accepted.json", "--junit", "out/check.xml"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  // Point a has surface_behind: 12 metrics; b and c 10 each.
  EXPECT_NE(r.out.find("err-sim check: 32 metrics: 32 pass, 0 within noise, 0 fail\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the same chain"), std::string::npos) << r.out;
  EXPECT_EQ(JUnitCounts(Path("out/check.xml")), "32 0 0\n");
  const Json accepted = ReadJson("in/accepted.json");
  ExpectVerdicts(accepted, accepted, r.out, 0.10, 3);
}

// The text reads right: the systematic offset's visual angle beside its size; no share of a whole
// that is zero to rounding ("none", no advice); no name cut in the Sobol table; the sweep's
// per-parameter figure called a gain, not a slope (a slope is one output's).
TEST_F(CliErrSim, TextSummariesReadRight) {
  Json c = SmallChain();
  c["display"]["eye_centre"] = {0.0, 0.0, -100.0};  // eyes 100 mm behind the cameras
  WriteJson("in/chain.json", c);
  CommandResult r = Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--samples", "400", "--without", "display"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json report = ReadJson("out/r.json");
  EXPECT_NE(r.err.find("systematic  its angle"), std::string::npos) << r.err;
  // Point b's row: the size, then the angle the JSON has, to 3 decimals.
  char angle[32];
  std::snprintf(angle, sizeof angle, "%.3f", report["test_points"][1]["misperception"]["systematic"]["angular_deg"].get<double>());
  EXPECT_NE(r.err.find(std::string("    b               100.00      ") + angle), std::string::npos) << r.err;
  EXPECT_TRUE(report["budget"]["whole"]["misperception"]["none"].get<bool>());
  EXPECT_TRUE(report["budget"]["entries"][0]["share_of_misperception_ms"].is_null());
  const std::string misperception = r.err.substr(r.err.find("error budget of the misperception"));
  EXPECT_NE(misperception.find("(none: the whole chain's is 0 to rounding)"), std::string::npos) << misperception;
  EXPECT_EQ(misperception.find("→"), std::string::npos) << misperception;
  EXPECT_EQ(misperception.find("100.0 %"), std::string::npos) << misperception;
  r = Run("err-sim", {"sobol", "in/chain.json", "-o", "out/s.json", "--samples", "64", "--bootstrap", "5"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.err.find("tracker_alignment  tracking"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("virtual_object_alignment"), std::string::npos) << r.err;
  r = Run("err-sim", {"sweep", "in/chain.json", "-o", "out/w.json", "--parameter", "tracking.latency", "--points", "3"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.err.find("image gain"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("slope at nominal"), std::string::npos) << r.err;
}

// A report of the previous version (@2: the budget's shares were of the sum of the parts) stays an
// accepted report: check reads only its per-point statistics, which did not change.
TEST_F(CliErrSim, CheckReadsAVersion2Report) {
  WriteJson("in/chain.json", SmallChain());
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "in/accepted.json", "--no-budget", "-q"}).exit_code, kOk);
  Json v2 = ReadJson("in/accepted.json");
  v2["format"] = "vstcal/err-sim-report@2";
  WriteJson("in/v2.json", v2);
  const CommandResult r = Run("err-sim", {"check", "in/v2.json", "--report", "in/accepted.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.out.find("32 metrics: 32 pass"), std::string::npos) << r.out;
  v2["format"] = "vstcal/err-sim-report@1";
  WriteJson("in/v1.json", v2);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"check", "in/v1.json", "--report", "in/accepted.json"}), "err-sim", kBadInput,
                        "in/v1.json: format: unsupported version", {"vstcal/err-sim-report@3"}));
}

// Eye terms shared or correlated: a correlation outside [-1, 1], or a term both shared and per
// eye, is one line naming the field and the fix, exit 2, nothing written; a valid one runs.
TEST_F(CliErrSim, SharedAndCorrelatedEyeTerms) {
  Json c = SmallChain();
  c["sources"]["camera_intrinsic"] = {{"shared", {{"fx", Normal(1.0)}}}, {"both", {{"cx", Normal(1.0)}}}, {"correlation", {{"cx", 0.9}}}};
  WriteJson("in/chain.json", c);
  const CommandResult r = Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--samples", "500", "--no-budget", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  std::filesystem::remove(Path("out/r.json"));
  c["sources"]["camera_intrinsic"]["correlation"]["cx"] = -1.2;
  WriteJson("in/chain.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--html", "out/r.html"}), "err-sim", kBadInput,
                        "in/chain.json: sources.camera_intrinsic.correlation.cx: must lie within [-1, 1], got -1.2",
                        {"-1 ≤ ρ ≤ 1"}));
  c["sources"]["camera_intrinsic"]["correlation"]["cx"] = 0.5;
  c["sources"]["camera_intrinsic"]["both"]["fx"] = Normal(1.0);
  WriteJson("in/chain.json", c);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json"}), "err-sim", kBadInput,
                        "in/chain.json: sources.camera_intrinsic.shared.fx: given in both \"shared\" and \"both\"",
                        {"give the term once"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"normalize", "in/chain.json", "-o", "out/n.json"}), "err-sim", kBadInput,
                        "in/chain.json: sources.camera_intrinsic.shared.fx: ", {}));
  EXPECT_TRUE(OutDirEmpty());
}

// Tracking four times as noisy: the misregistration rises far beyond 10 % and its noise; the check
// fails — from a given report and from a re-run of the changed chain alike.
TEST_F(CliErrSim, CheckFailsWhenAMetricRisesBeyondNoise) {
  WriteJson("in/chain.json", SmallChain());
  Json worse = SmallChain();
  worse["sources"]["tracking"]["translation"] = Normal(4.0);
  WriteJson("in/worse.json", worse);
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "in/accepted.json", "--no-budget", "-q"}).exit_code, kOk);
  ASSERT_EQ(Run("err-sim", {"run", "in/worse.json", "-o", "in/new.json", "--no-budget", "-q"}).exit_code, kOk);
  CommandResult r = Run("err-sim", {"check", "in/accepted.json", "--report", "in/new.json", "--junit", "out/check.xml"});
  EXPECT_EQ(r.exit_code, kCheckFailed) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto counts = ExpectVerdicts(ReadJson("in/accepted.json"), ReadJson("in/new.json"), r.out, 0.10, 3);
  ASSERT_GT(counts.count("fail"), 0u);
  // A tracking translation error moves the overlay sideways: the lateral misregistration rises
  // beyond noise, while the depth error (the intrinsics' disparity, unchanged) and so the linear
  // one, which it dominates at these points, stay.
  EXPECT_EQ(PrintedVerdict(r.out, "b.misregistration.lateral"), "fail") << r.out;
  EXPECT_EQ(PrintedVerdict(r.out, "b.misregistration.depth_abs"), "pass") << r.out;
  EXPECT_NE(r.out.find(" fail (exit code 4)\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the chain changed"), std::string::npos) << r.out;
  EXPECT_EQ(JUnitCounts(Path("out/check.xml")), "32 " + std::to_string(counts.at("fail")) + " " + std::to_string(counts.at("fail")) + "\n");

  // The same through a re-run of the changed chain (same samples and seed as the accepted run).
  r = Run("err-sim", {"check", "in/accepted.json", "--chain", "in/worse.json", "-q"});
  EXPECT_EQ(r.exit_code, kCheckFailed) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;  // -q: the exit code says it
  // A generous allowance for misregistration passes those metrics.
  r = Run("err-sim", {"check", "in/accepted.json", "--report", "in/new.json", "--max-rise", "misregistration.linear=50",
                      "--max-rise", "b.misregistration.lateral=1000%"});
  EXPECT_EQ(PrintedVerdict(r.out, "b.misregistration.linear"), "pass");
  EXPECT_EQ(PrintedVerdict(r.out, "c.misregistration.linear"), "pass");
  EXPECT_EQ(PrintedVerdict(r.out, "b.misregistration.lateral"), "pass");
}

// The same chain with another seed: the metrics move by sampling noise only. With almost no
// allowance (0.001 %) every metric that rose is "within noise", and none fails: noise fails no build.
TEST_F(CliErrSim, CheckCallsASampleNoiseRiseWithinNoise) {
  WriteJson("in/chain.json", SmallChain());
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "in/accepted.json", "--no-budget", "-q"}).exit_code, kOk);
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "in/new.json", "--no-budget", "-q", "--seed", "8"}).exit_code, kOk);
  const CommandResult r =
      Run("err-sim", {"check", "in/accepted.json", "--report", "in/new.json", "--max-rise", "0.001%", "--junit", "out/c.xml"});
  ASSERT_EQ(r.exit_code, kOk) << r.out << r.err;
  const auto counts = ExpectVerdicts(ReadJson("in/accepted.json"), ReadJson("in/new.json"), r.out, 0.00001, 3);
  EXPECT_EQ(counts.count("fail"), 0u);
  EXPECT_GT(counts.count("within noise"), 0u);
  EXPECT_EQ(JUnitCounts(Path("out/c.xml")), "32 0 0\n");
  // At z = 0.5 the same rises are no longer explained by noise: some fail.
  const CommandResult strict = Run("err-sim", {"check", "in/accepted.json", "--report", "in/new.json", "--max-rise", "0.001%", "--z", "0.5"});
  EXPECT_EQ(strict.exit_code, kCheckFailed);
  EXPECT_GT(ExpectVerdicts(ReadJson("in/accepted.json"), ReadJson("in/new.json"), strict.out, 0.00001, 0.5).count("fail"), 0u);
}

TEST_F(CliErrSim, CheckRefusesBadThresholdsAndNames) {
  WriteJson("in/chain.json", SmallChain());
  ASSERT_EQ(Run("err-sim", {"run", "in/chain.json", "-o", "in/accepted.json", "--no-budget", "-q"}).exit_code, kOk);
  for (const char* bad : {"0", "-5%", "nan", "inf", "0%", "ten", "b.misregistration.linear=0"}) {
    EXPECT_TRUE(FailsWith(Run("err-sim", {"check", "in/accepted.json", "--report", "in/accepted.json",
                                          "--max-rise=" + std::string(bad), "--junit", "out/c.xml"}),
                          "err-sim", kBadInput, "--max-rise: \"" + std::string(bad) + "\": not a positive amount",
                          {"PERCENT%"}))
        << bad;
  }
  EXPECT_TRUE(FailsWith(Run("err-sim", {"check", "in/accepted.json", "--report", "in/accepted.json", "--max-rise", "5%",
                                        "--max-rise", "0.5"}),
                        "err-sim", kBadInput, "--max-rise: \"0.5\": a second default", {}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"check", "in/accepted.json", "--report", "in/accepted.json", "--max-rise",
                                        "misregistration.linaer=10%"}),
                        "err-sim", kBadInput, "--max-rise: \"misregistration.linaer\": no such metric",
                        {"did you mean \"misregistration.linear\""}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"check", "in/accepted.json", "--report", "in/accepted.json", "--z", "0"}), "err-sim",
                        kBadInput, "--z: 0 is not a positive number", {}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"check", "in/accepted.json", "--report", "in/accepted.json", "--chain", "in/chain.json"}),
                        "err-sim", kBadInput, "--chain: ", {"drop one of the two"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"check", "in/chain.json", "--junit", "out/c.xml"}), "err-sim", kBadInput,
                        "in/chain.json: format: ", {"vstcal/err-sim-report@3"}));
  EXPECT_TRUE(FailsWith(Run("err-sim", {"check", "in/accepted.json", "--report", "in/accepted.json", "--junit",
                                        "in/accepted.json"}),
                        "err-sim", kBadInput, "in/accepted.json", {"input"}));
  EXPECT_TRUE(OutDirEmpty());
}

// An unrefined calib-dlt camera carries the DLT's first-order covariance (docs/math/dlt.md#covariance)
// in the form refined cameras use: err-sim's "covariance": "camera" reads it, and the image error
// it causes grows with the calibration's pixel noise.
TEST_F(CliErrSim, CovarianceOfAnUnrefinedDltCamera) {
  double rms[2];
  for (int k = 0; k < 2; ++k) {
    const std::string noise = k == 0 ? "0.25" : "1";
    Synth("in/volume.json", Override(DefaultSynthArgs(), "--noise", noise));
    ASSERT_EQ(Run("calib-dlt", {"in/volume.json", "-o", "in/dlt.camera.json", "-q"}).exit_code, kOk);
    ASSERT_TRUE(ReadJson("in/dlt.camera.json").contains("covariance"));
    Json c = SmallChain();
    c["cameras"]["left"] = {{"file", "dlt.camera.json"}};
    c["sources"]["camera_intrinsic"] = {{"left", {{"covariance", "camera"}}}};
    WriteJson("in/chain.json", c);
    const CommandResult r =
        Run("err-sim", {"run", "in/chain.json", "-o", "out/r.json", "--only", "camera_intrinsic", "--no-budget", "-q"});
    ASSERT_EQ(r.exit_code, kOk) << r.err;
    EXPECT_EQ(r.err.find("has no covariance"), std::string::npos) << r.err;
    rms[k] = ReadJson("out/r.json")["totals"]["image_rms_px"].get<double>();
  }
  EXPECT_GT(rms[0], 0.0);
  EXPECT_GT(rms[1], 2 * rms[0]);  // σ̂ 4× larger: the covariance 16×, the error ≈ 4×
}

}  // namespace
}  // namespace vstcal::cli_test
