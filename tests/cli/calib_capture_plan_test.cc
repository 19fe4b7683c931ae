// CLI tests of calib-capture plan: the JSON and text outputs, a nominal camera in mm equal to the
// same camera in px, and every bad input with its exit code, one line naming the flag or file
// and the fix, nothing written, and the inputs untouched.
#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

constexpr std::string_view kTool = "calib-capture";

class CliCapturePlan : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    const CommandResult r = Run(kTool, {"target", "--rows", "9", "--cols", "13", "--square-size", "100", "--dpi", "0", "-o", "in/board"});
    ASSERT_EQ(r.exit_code, kOk) << r.err;
  }
  // A volume of 5 planes 500 mm apart, 3 m from a 1280×1024 camera of fx 1400 px.
  static std::vector<std::string> Args() {
    return {"plan", "in/board.target.json", "--image-size", "1280x1024", "--fx", "1400", "--near", "0", "--far", "2000",
            "--interval", "500", "--camera-distance", "3000", "-o", "out/plan.json"};
  }
};

TEST_F(CliCapturePlan, WritesThePlanAndItsPrediction) {
  const CommandResult r = Run(kTool, Args());
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json plan = ReadJson("out/plan.json");
  EXPECT_EQ(plan["format"], "vstcal/capture-plan@1");
  ASSERT_EQ(plan["positions"].size(), 5u);
  // Fronto-parallel: the near plane's squares span f·s/Z = 1400·100/3000 px.
  EXPECT_NEAR(plan["positions"][0]["smallest_square_px"].get<double>(), 1400.0 * 100 / 3000, 1e-6);
  EXPECT_TRUE(plan["prediction"]["observable"].get<bool>());
  EXPECT_EQ(plan["prediction"]["parameters"][0]["name"], "fx");
  EXPECT_GT(plan["prediction"]["parameters"][0]["sigma"].get<double>(), 0);
  EXPECT_EQ(plan["prediction"]["test_points"].size(), 5u);  // seed 000's five
  EXPECT_NE(r.err.find("fx"), std::string::npos);           // the text summary

  // The same camera from a focal length in mm and the pixel pitch: 7 mm / 5 µm = 1400 px.
  std::vector<std::string> mm = Override(Remove(Args(), "--fx"), "--focal-mm", "7");
  mm = Override(Override(mm, "--pixel-pitch-um", "5"), "-o", "out/mm.json");
  ASSERT_EQ(Run(kTool, mm).exit_code, kOk);
  EXPECT_EQ(ReadJson("out/mm.json")["prediction"], plan["prediction"]);

  ASSERT_EQ(Run(kTool, Override(Override(Args(), "--format", "text"), "-o", "out/plan.txt")).exit_code, kOk);
  EXPECT_NE(ReadText("out/plan.txt").find("z=2000"), std::string::npos);
}

TEST_F(CliCapturePlan, BadInputIsOneLineNothingWritten) {
  struct Case {
    std::vector<std::string> args;
    int exit_code;
    std::string location;
    std::vector<std::string> phrases;
  };
  const std::vector<Case> cases = {
      {Remove(Args(), "--fx"), kBadInput, "--camera: ", {"--fx"}},
      {Override(Remove(Args(), "--fx"), "--focal-mm", "7"), kBadInput, "--focal-mm: ", {"--pixel-pitch-um"}},
      {Remove(Args(), "--image-size"), kBadInput, "--image-size: ", {"required"}},
      {Override(Args(), "--pixel-sigma", "0"), kBadInput, "--pixel-sigma", {}},
      {Override(Args(), "--views", "5"), kBadInput, "--views: ", {"--rig"}},
      {Override(Args(), "--test-point", "1,2"), kBadInput, "--test-point: ", {"X,Y,Z"}},
      {Override(Args(), "--depth-of-field", "3000,2000"), kBadInput, "--depth-of-field: ", {"NEAR < FAR"}},
      {Override(Args(), "--interval", "-5"), kBadInput, "--interval: ", {"positive"}},
      {Override(Args(), "--distortion", "k9"), kBadInput, "k9", {}},
      {Override(Override(Args(), "--camera-distance", "300"), "--far", "0"), kDegenerate, "no planned position", {"move the camera back"}},
      {Override(Args(), "-o", "in/board.target.json"), kBadInput, "in/board.target.json: ", {"never overwrites its inputs"}},
  };
  const std::string target = ReadText("in/board.target.json");
  for (const Case& c : cases) {
    const CommandResult r = Run(kTool, c.args);
    EXPECT_TRUE(FailsWith(r, kTool, c.exit_code, c.location, c.phrases)) << c.args.back() << " " << r.err;
    EXPECT_TRUE(OutDirEmpty());
  }
  EXPECT_EQ(ReadText("in/board.target.json"), target);
  WriteText("in/broken.target.json", "{\"format\": \"vstcal/target@1\", \"type\": ");
  std::vector<std::string> broken = Args();
  broken[1] = "in/broken.target.json";
  EXPECT_TRUE(FailsWith(Run(kTool, broken), kTool, kBadInput, "in/broken.target.json: ", {}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCapturePlan, CompareTwoPlans) {
  ASSERT_EQ(Run(kTool, Override(Args(), "-o", "in/a.json")).exit_code, kOk);
  ASSERT_EQ(Run(kTool, Override(Override(Args(), "-o", "in/b.json"), "--tilt-deg", "30")).exit_code, kOk);
  const CommandResult r = Run(kTool, {"plan", "--compare", "in/a.json", "in/b.json", "-o", "out/cmp.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json a = ReadJson("in/a.json"), b = ReadJson("in/b.json"), cmp = ReadJson("out/cmp.json");
  EXPECT_EQ(cmp["format"], "vstcal/capture-plan-comparison@1");
  ASSERT_EQ(cmp["parameters"].size(), a["prediction"]["parameters"].size());
  for (size_t i = 0; i < cmp["parameters"].size(); ++i) {
    const double sa = a["prediction"]["parameters"][i]["sigma"], sb = b["prediction"]["parameters"][i]["sigma"];
    EXPECT_EQ(cmp["parameters"][i]["ratio"].get<double>(), sb / sa);
    EXPECT_EQ(cmp["parameters"][i]["better"], sb < sa ? "B" : "A");
  }
  ASSERT_EQ(cmp["test_points_with_poses_px"].size(), 5u);

  // Plans at different pixel noise, a broken plan, a plan flag beside --compare.
  ASSERT_EQ(Run(kTool, Override(Override(Args(), "-o", "in/c.json"), "--pixel-sigma", "0.5")).exit_code, kOk);
  EXPECT_TRUE(FailsWith(Run(kTool, {"plan", "--compare", "in/a.json", "in/c.json", "-o", "out/x.json"}), kTool, kBadInput,
                        "in/c.json: prediction.pixel_sigma: ", {"same --pixel-sigma"}));
  WriteText("in/broken.json", "{\"format\": \"vstcal/capture-plan@1\", \"prediction\": {}}");
  EXPECT_TRUE(FailsWith(Run(kTool, {"plan", "--compare", "in/a.json", "in/broken.json", "-o", "out/x.json"}), kTool, kBadInput,
                        "in/broken.json: ", {}));
  EXPECT_TRUE(FailsWith(Run(kTool, {"plan", "--compare", "in/a.json", "in/b.json", "--fx", "3", "-o", "out/x.json"}), kTool,
                        kBadInput, "--fx: ", {"remove --fx"}));
  EXPECT_TRUE(FailsWith(Run(kTool, {"plan", "--compare", "in/a.json", "in/b.json", "-o", "in/a.json"}), kTool, kBadInput,
                        "in/a.json: ", {"never overwrites its inputs"}));
  EXPECT_EQ(ReadJson("in/a.json"), a);
  EXPECT_EQ(List("out"), std::vector<std::string>{"cmp.json"});  // no x.json from the failures
}

}  // namespace
}  // namespace vstcal::cli_test
