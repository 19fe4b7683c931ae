// Inputs are never overwritten (docs/reliability.md#inputs): for every tool, an output that names an
// input — spelled the same, as ./name, through a symlink or a hard link — and two outputs naming
// one file are refused with exit code 2 and one line, before any work, and the input keeps its
// bytes.
#include <unistd.h>

#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

class CliInputsSacred : public CliTest {
 protected:
  // The refusal contract: exit 2, one line naming the output and saying it is an input, the input
  // unchanged, out/ empty.
  void ExpectRefused(std::string_view tool, const std::vector<std::string>& args, const std::string& input,
                     const std::string& output) {
    const std::string before = ReadText(input);
    const CommandResult r = Run(tool, args);
    EXPECT_TRUE(FailsWith(r, tool, kBadInput, output + ": ", {"is the input", "never overwrites its inputs"}));
    EXPECT_EQ(ReadText(input), before) << input << " was changed";
    EXPECT_TRUE(OutDirEmpty());
  }

  // A pinhole camera file, written by calib-synth as a truth file.
  void WriteCamera(const std::string& relative) {
    Synth("in/cam-source.json");
    fs::copy_file(Path("in/cam-source.truth.json"), Path(relative), fs::copy_options::overwrite_existing);
  }

  // seed 001's chain and the camera it references, copied so that the chain's relative path holds.
  void CopyChain() {
    fs::create_directories(Path("in/vst"));
    fs::create_directories(Path("in/zedmini"));
    fs::copy_file(fs::path(VSTCAL_SOURCE_DIR) / "datasets/vst/seed001.json", Path("in/vst/chain.json"));
    fs::copy_file(fs::path(VSTCAL_SOURCE_DIR) / "datasets/zedmini/clean.truth.json", Path("in/zedmini/clean.truth.json"));
  }
};

TEST_F(CliInputsSacred, CalibDltOutputIsTheInput) {
  Synth("in/volume.json");
  ExpectRefused("calib-dlt", {"in/volume.json", "-o", "in/volume.json"}, "in/volume.json", "in/volume.json");
  ExpectRefused("calib-dlt", {"in/volume.json", "-o", "./in/../in/volume.json"}, "in/volume.json",
                "./in/../in/volume.json");
  ExpectRefused("calib-dlt", {"in/volume.json", "-o", "out/c.json", "--residuals", "in/volume.json"}, "in/volume.json",
                "in/volume.json");
}

TEST_F(CliInputsSacred, CalibDltOutputIsASymlinkOrHardLinkToTheInput) {
  Synth("in/volume.json");
  fs::create_symlink(Path("in/volume.json"), Path("in/link.json"));
  ExpectRefused("calib-dlt", {"in/volume.json", "-o", "in/link.json"}, "in/volume.json", "in/link.json");
  fs::create_hard_link(Path("in/volume.json"), Path("in/hard.json"));
  ExpectRefused("calib-dlt", {"in/volume.json", "-o", "in/hard.json"}, "in/volume.json", "in/hard.json");
  // The input given through the link, the output by its own name.
  ExpectRefused("calib-dlt", {"in/link.json", "-o", "in/volume.json"}, "in/volume.json", "in/volume.json");
}

TEST_F(CliInputsSacred, TwoOutputsThatAreOneFile) {
  Synth("in/volume.json");
  WriteText("out/a.json", "old");
  ASSERT_EQ(::link(Path("out/a.json").c_str(), Path("out/b.json").c_str()), 0);
  const CommandResult r =
      Run("calib-dlt", {"in/volume.json", "-o", "out/a.json", "--residuals", "out/b.json"});
  EXPECT_TRUE(FailsWith(r, "calib-dlt", kBadInput, "out/b.json: ", {"the same file is given for two outputs"}));
  EXPECT_EQ(ReadText("out/a.json"), "old");
}

TEST_F(CliInputsSacred, CalibTsaiOutputIsTheInput) {
  Synth("in/volume.json");
  ExpectRefused("calib-tsai", {"in/volume.json", "-o", "in/volume.json"}, "in/volume.json", "in/volume.json");
  ExpectRefused("calib-tsai", {"in/volume.json", "-o", "out/c.json", "--residuals", "./in/volume.json"},
                "in/volume.json", "./in/volume.json");
}

TEST_F(CliInputsSacred, CalibSynthTruthIsTheCamera) {
  WriteCamera("in/camera.json");
  ExpectRefused("calib-synth", {"--camera", "in/camera.json", "-o", "out/v.json", "--truth", "in/camera.json"},
                "in/camera.json", "in/camera.json");
  // The default truth name (OUTPUT with .truth.json) is an output too.
  WriteCamera("in/v.truth.json");
  ExpectRefused("calib-synth", {"--camera", "in/v.truth.json", "-o", "in/v.json"}, "in/v.truth.json",
                "in/v.truth.json");
  EXPECT_FALSE(fs::exists(Path("in/v.json")));
}

TEST_F(CliInputsSacred, CalibConvertOutputIsTheInput) {
  WriteCamera("in/camera.json");
  ExpectRefused("calib-convert", {"in/camera.json", "-o", "in/camera.json"}, "in/camera.json", "in/camera.json");
  fs::create_symlink("camera.json", Path("in/camera-link.json"));
  ExpectRefused("calib-convert", {"in/camera.json", "-o", "in/camera-link.json"}, "in/camera.json",
                "in/camera-link.json");
}

TEST_F(CliInputsSacred, ErrSimRunOutputIsTheChainOrItsCamera) {
  CopyChain();
  const std::vector<std::string> fast = {"--samples", "200", "--no-budget", "-q"};
  auto run = [&](const std::string& output) {
    std::vector<std::string> args = {"run", "in/vst/chain.json", "-o", output};
    args.insert(args.end(), fast.begin(), fast.end());
    return args;
  };
  ExpectRefused("err-sim", run("in/vst/chain.json"), "in/vst/chain.json", "in/vst/chain.json");
  // The camera file the chain references is an input too.
  ExpectRefused("err-sim", run("in/zedmini/clean.truth.json"), "in/zedmini/clean.truth.json",
                "in/zedmini/clean.truth.json");
}

TEST_F(CliInputsSacred, ErrSimSensitivityAndNormalizeOutputIsTheChain) {
  CopyChain();
  ExpectRefused("err-sim", {"sweep", "in/vst/chain.json", "-o", "in/vst/chain.json", "--points", "3"},
                "in/vst/chain.json", "in/vst/chain.json");
  ExpectRefused("err-sim", {"sobol", "in/vst/chain.json", "-o", "./in/vst/chain.json", "--samples", "64"},
                "in/vst/chain.json", "./in/vst/chain.json");
  ExpectRefused("err-sim", {"linear", "in/vst/chain.json", "-o", "in/vst/chain.json", "--samples", "100"},
                "in/vst/chain.json", "in/vst/chain.json");
  // normalize rewrites a chain: "in place" through a hard link is still the input.
  fs::create_hard_link(Path("in/vst/chain.json"), Path("in/vst/link.json"));
  ExpectRefused("err-sim", {"normalize", "in/vst/chain.json", "-o", "in/vst/link.json"}, "in/vst/chain.json",
                "in/vst/link.json");
}

TEST_F(CliInputsSacred, ErrSimMergeOutputIsAShard) {
  CopyChain();
  for (const char* shard : {"0/2", "1/2"}) {
    const std::string name = std::string("in/shard") + shard[0] + ".json";
    const CommandResult r =
        Run("err-sim", {"run", "in/vst/chain.json", "-o", name, "--samples", "200", "--no-budget", "-q", "--shard", shard});
    ASSERT_EQ(r.exit_code, kOk) << r.err;
  }
  ExpectRefused("err-sim", {"merge", "in/vst/chain.json", "in/shard0.json", "in/shard1.json", "-o", "in/shard1.json"},
                "in/shard1.json", "in/shard1.json");
}

}  // namespace
}  // namespace vstcal::cli_test
