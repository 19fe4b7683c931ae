// CLI tests of err-sim: bad chains and flags get exit code 2 and one line naming the file, the field
// and the fix (with a did-you-mean for unknown keys), and no output file; good runs are
// reproducible for any thread count and shard split.
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
  EXPECT_EQ(report["format"], "vstcal/err-sim-report@1");
  EXPECT_EQ(report["samples"], 3000);
  EXPECT_EQ(report["test_points"].size(), 3u);
  EXPECT_EQ(report["budget"]["entries"].size(), 7u);
  EXPECT_TRUE(report["test_points"][0]["occlusion"].is_object());
  EXPECT_TRUE(report["test_points"][1]["occlusion"].is_null());
  EXPECT_EQ(report["provenance"]["tool"], "err-sim");
  EXPECT_EQ(report["provenance"]["seed"], 7);  // from the chain file: the seed the run used
  for (const Json& e : report["budget"]["entries"]) {
    if (e["source"] == "display") {
      EXPECT_LT(e["alone"]["image_rms_px"].get<double>(), 1e-9);  // display errors cancel in the image (to rounding)
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
    EXPECT_EQ(ReadJson("out/s" + i + ".json")["format"], "vstcal/err-sim-shard@1");
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
  EXPECT_EQ(sweep["format"], "vstcal/err-sim-sweep@1");
  EXPECT_EQ(sweep["parameters"][0]["values"].size(), 21u);
  ASSERT_EQ(Run("err-sim", {"sobol", "in/chain.json", "-o", "out/sobol.json", "--samples", "256", "--bootstrap", "20", "-q"}).exit_code, kOk);
  EXPECT_EQ(ReadJson("out/sobol.json")["groups"].size(), 7u);
  ASSERT_EQ(Run("err-sim", {"linear", "in/chain.json", "-o", "out/linear.json", "--samples", "2000", "-q"}).exit_code, kOk);
  EXPECT_EQ(ReadJson("out/linear.json")["outputs"].size(), 21u);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sweep", "in/chain.json", "-o", "out/x.json", "--parameter", "display.ipdd"}), "err-sim",
                        kBadInput, "", {"display.ipdd"}));
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

}  // namespace
}  // namespace vstcal::cli_test
