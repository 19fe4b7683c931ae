// CLI tests of the rules every tool follows (docs/conventions.md#exit-codes, docs/reliability.md),
// at the edges issue 24's audit found them broken: a failed write to stdout, inputs that are not
// regular files, output folders that do not exist, mistyped flags.
#include <sys/stat.h>

#include <fstream>

#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

using CliToolRules = CliTest;

std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// What a tool prints on stdout is its output: lost to a full disk (/dev/full), the run fails with
// the documented exit code and one line, and reproj-report leaves no report file behind.
TEST_F(CliToolRules, AFailedWriteToStdoutIsAnError) {
  Synth();
  const std::vector<std::string> compare = {"in/volume.truth.json", "in/volume.truth.json"};
  ASSERT_EQ(RunWithStdout("calib-compare", compare, Path("in/table.txt")).exit_code, kOk);
  EXPECT_NE(ReadText("in/table.txt").find("rotation difference"), std::string::npos);
  EXPECT_TRUE(FailsWith(RunWithStdout("calib-compare", compare, "/dev/full"), "calib-compare", kBadInput,
                        "standard output: cannot write (No space left on device)", {"the output is lost"}));

  ASSERT_EQ(Run("calib-dlt", {"in/volume.json", "-o", "in/cam.json", "-q"}).exit_code, kOk);
  const std::vector<std::string> report = {"in/cam.json", "in/volume.json", "-o", "out/report.json", "--format", "text"};
  EXPECT_TRUE(FailsWith(RunWithStdout("reproj-report", report, "/dev/full"), "reproj-report", kBadInput,
                        "standard output: cannot write (No space left on device)", {}));
  EXPECT_TRUE(OutDirEmpty());
  EXPECT_TRUE(FailsWith(RunWithStdout("calib-compare", {"--help"}, "/dev/full"), "calib-compare", kBadInput,
                        "standard output: cannot write", {}));
}

// A device or a pipe has no size and may never end (/dev/zero was read to 256 MiB) or block the
// open (a FIFO nobody writes to): refused before it is opened, as JSON, as an image or as YAML;
// and a YAML file is held to YAML's own limit (16 MiB) from the start, not read to JSON's 256 MiB.
TEST_F(CliToolRules, InputsThatAreNotRegularFilesAreRefusedAtOnce) {
  EXPECT_TRUE(FailsWith(Run("calib-dlt", {"/dev/zero", "-o", "out/cam.json"}), "calib-dlt", kBadInput,
                        "/dev/zero: is not a regular file (a device, a pipe or a socket), not a JSON file", {"give the file itself"}));
  ASSERT_EQ(::mkfifo(Path("in/fifo.json").c_str(), 0600), 0);
  EXPECT_TRUE(FailsWith(Run("calib-dlt", {"in/fifo.json", "-o", "out/cam.json"}), "calib-dlt", kBadInput,
                        "in/fifo.json: is not a regular file", {}));
  ASSERT_EQ(Run("calib-capture", {"target", "--rows", "6", "--cols", "9", "--square-size", "25", "--dpi", "0", "-o", "in/board"}).exit_code, kOk);
  EXPECT_TRUE(FailsWith(Run("calib-capture", {"detect", "in/board.target.json", "/dev/zero", "-o", "out/c.json"}), "calib-capture",
                        kBadInput, "/dev/zero: is not a regular file (a device, a pipe or a socket), not an image", {}));
  {
    std::ofstream big(Path("in/big.yaml"));
    big << "%YAML:1.0\n";
  }
  fs::resize_file(Path("in/big.yaml"), (size_t{300} << 20));  // sparse: no disk space taken
  EXPECT_TRUE(FailsWith(Run("calib-convert", {"in/big.yaml", "-o", "out/cam.json"}), "calib-convert", kBadInput,
                        "in/big.yaml: larger than the 16 MiB vstcal reads as OpenCV YAML", {}));
  EXPECT_TRUE(OutDirEmpty());
}

// A mistyped flag gets the closest known one, of the tool or of the subcommand given (issue 24).
TEST_F(CliToolRules, AnUnknownFlagGetsADidYouMean) {
  Synth();
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/volume.truth.json", "in/volume.truth.json", "--dpeth", "1700"}), "calib-compare",
                        kBadInput, "--dpeth", {"(did you mean --depth?)", "see calib-compare --help"}));
  EXPECT_TRUE(FailsWith(Run("calib-stereo", {"solve", "in/volume.json", "in/volume.json", "-o", "out/rig.json", "--hold-lef"}),
                        "calib-stereo", kBadInput, "--hold-lef", {"(did you mean --hold-left?)"}));
  EXPECT_TRUE(FailsWith(Run("calib-dlt", {"in/volume.json", "-o", "out/cam.json", "--zzzzzzzz"}), "calib-dlt", kBadInput,
                        "--zzzzzzzz", {"see calib-dlt --help"}));
}

// Range messages say what is wanted, not CLI11's "not in range 0 to 1797693134862315708…" (309
// digits) of CLI::PositiveNumber.
TEST_F(CliToolRules, RangeMessagesAreShort) {
  Synth();
  const CommandResult depth = Run("calib-compare", {"in/volume.truth.json", "in/volume.truth.json", "--depth", "-5"});
  EXPECT_TRUE(FailsWith(depth, "calib-compare", kBadInput, "--depth", {"expected a positive number, got \"-5\""}));
  EXPECT_LT(depth.err.size(), 200u) << depth.err;
  const CommandResult every = Run("calib-capture", {"detect", "in/volume.json", "--video", "in/v.avi", "--every", "0", "-o", "out/c.json"});
  EXPECT_TRUE(FailsWith(every, "calib-capture", kBadInput, "--every", {"expected a whole number ≥ 1, got \"0\""}));
  EXPECT_LT(every.err.size(), 200u) << every.err;
}

// -q leaves out the summary in every tool, calib-synth included (issue 24: it had no -q).
TEST_F(CliToolRules, CalibSynthIsQuietWithQ) {
  std::vector<std::string> args = DefaultSynthArgs();
  args.insert(args.end(), {"-o", "out/volume.json", "-q"});
  const CommandResult r = Run("calib-synth", args);
  EXPECT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(List("out"), (std::vector<std::string>{"volume.json", "volume.truth.json"}));
}

// NaN and infinity are never written (docs/conventions.md#numbers-in-files): seed 001's chain with
// a tracking σ of 1e300 mm squares to infinity in J Σ Jᵀ, which err-sim linear printed as "inf" and
// "-nan %" and wrote as null (issue 24); it is refused, naming the chain and the parameter.
TEST_F(CliToolRules, ErrSimRefusesResultsBeyondDoublePrecision) {
  Json chain = Json::parse(ReadTextFile(std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/seed001.json"));
  for (const char* eye : {"left", "right"}) {
    chain["cameras"][eye]["file"] = std::string(VSTCAL_SOURCE_DIR) + "/datasets/zedmini/clean.truth.json";
  }
  chain["samples"] = 2000;
  chain["sources"]["tracking"]["translation"]["sigma"] = 1e300;
  WriteJson("in/chain.json", chain);
  EXPECT_TRUE(FailsWith(Run("err-sim", {"linear", "in/chain.json", "-o", "out/linear.json"}), "err-sim", kBadInput,
                        "in/chain.json: linear propagation: J Σ Jᵀ is beyond double precision", {"tracking.translation."}));
  EXPECT_TRUE(OutDirEmpty());
}

// Messages that named the wrong cause (issue 24), each with the right one now.
TEST_F(CliToolRules, MessagesNameTheRealCause) {
  Synth();
  // One coordinate of 1e308 was "collinear" points.
  Json far = ReadJson("in/volume.json");
  far["views"][0]["points"][3][0] = 1e308;
  WriteJson("in/far.json", far);
  EXPECT_TRUE(FailsWith(Run("calib-dlt", {"in/far.json", "-o", "out/cam.json"}), "calib-dlt", kDegenerate,
                        "one point, at (1e+308, ", {"check that point's coordinates"}));
  // A board in units of 1e200 (or 1e-300) was "degenerate (collinear?)", a volume "too few points,
  // or all on one line": the lengths are the problem, and the message says so.
  Synth("in/views.json", {"--image-size", "640x480", "--fx", "600", "--rig", "planar-views", "--views", "4", "--grid", "8x6",
                          "--spacing", "30", "--noise", "0.2"});
  for (const double scale : {1e200, 1e-300}) {
    Json views = ReadJson("in/views.json");
    for (Json& view : views["views"]) {
      for (Json& point : view["points"]) {
        for (int i = 0; i < 3; ++i) point[i] = point[i].get<double>() * scale;
      }
    }
    WriteJson("in/scaled.json", views);
    EXPECT_TRUE(FailsWith(Run("calib-tsai", {"in/scaled.json", "-o", "out/cam.json"}), "calib-tsai", kDegenerate,
                          "in/scaled.json: the board's points spread over ", {"beyond the lengths (1e-50 to 1e50)", "another length unit"}))
        << scale;
  }
  // An OpenCV YAML camera given to a tool that reads camera@1 JSON was "not valid JSON".
  ASSERT_EQ(Run("calib-convert", {"in/volume.truth.json", "-o", "in/cam.yaml"}).exit_code, kOk);
  EXPECT_TRUE(FailsWith(Run("calib-compare", {"in/volume.truth.json", "in/cam.yaml"}), "calib-compare", kBadInput,
                        "in/cam.yaml: line 1, column 1: not valid JSON: this is an OpenCV FileStorage YAML file",
                        {"calib-convert in/cam.yaml -o camera.json"}));
  // A folder was a file whose format "cannot be told from its name".
  EXPECT_TRUE(FailsWith(Run("calib-convert", {"in", "-o", "out/cam.json"}), "calib-convert", kBadInput,
                        "in: is a directory, not a camera file", {}));
  EXPECT_TRUE(OutDirEmpty());
}

}  // namespace
}  // namespace vstcal::cli_test
