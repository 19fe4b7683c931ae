// Shared fixture of the CLI tests: a fresh temporary directory per test (inputs in in/, outputs in
// out/), the tools run inside it with relative paths, and assertions for the error contract of
// docs/conventions.md#exit-codes: documented exit code, exactly one line on stderr
// "<tool>: error: <file>: <field>: <what is wrong>; <how to fix>", and no output file left behind.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "run_command.h"

namespace vstcal::cli_test {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// Exit codes (docs/conventions.md#exit-codes).
inline constexpr int kOk = 0;
inline constexpr int kBadInput = 2;
inline constexpr int kDegenerate = 3;
inline constexpr int kCheckFailed = 4;  // calib-compare --max-px/--max-sigma, err-sim check

// ${VSTCAL_TOOLS_DIR}/<tool>, or $VSTCAL_CLI_TOOLS_DIR/<tool> when that environment variable is set.
std::string ToolPath(std::string_view tool);

// The small volume most tests start from: a 640×480 camera with fx 600 and no noise, 1.5 m in
// front of a 5×4 grid (100 mm spacing) at Z = 0, 200 and 400 mm: 60 points in 3 views.
std::vector<std::string> DefaultSynthArgs();

// Replaces the value of `flag` in `args` (appending flag and value when it is absent); Remove
// drops the flag and, unless it is a bare switch, its value.
std::vector<std::string> Override(std::vector<std::string> args, const std::string& flag, const std::string& value);
std::vector<std::string> Remove(std::vector<std::string> args, const std::string& flag, bool has_value = true);

// A pinhole camera read back from a calib-synth truth file, to build geometric test cases.
struct Pinhole {
  Eigen::Matrix3d K;
  Eigen::Matrix3d R;  // camera_from_world
  Eigen::Vector3d t;

  static Pinhole FromTruth(const Json& truth);
  Eigen::Vector3d Centre() const { return -R.transpose() * t; }
  // [X, Y, Z, u, v] for a world point.
  Json Observe(const Eigen::Vector3d& point_in_world) const;
};

// 1-based "line L, column C" of a byte offset in a text, as the tools report it. Written here
// again on purpose, not taken from json/reader_common: the expected message must not come from
// the code under test.
std::string LineColumn(const std::string& text, size_t offset);

// A JUnit XML file as Debian's Python reads it (xml.etree; a file that is not well-formed fails the
// test): "<testcases> <the testsuite's failures attribute> <failure elements>\n".
std::string JUnitCounts(const fs::path& file);

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  const fs::path& dir() const { return dir_; }
  fs::path Path(const std::string& relative) const { return dir_ / relative; }

  void WriteText(const std::string& relative, const std::string& text) const;
  std::string ReadText(const std::string& relative) const;
  void WriteJson(const std::string& relative, const Json& json) const { WriteText(relative, json.dump(2) + "\n"); }
  Json ReadJson(const std::string& relative) const { return Json::parse(ReadText(relative)); }

  // Runs a tool from the build tree with the test directory as working directory.
  CommandResult Run(std::string_view tool, const std::vector<std::string>& args) const;
  // The same with the tool's stdout going to `stdout_to` (e.g. /dev/full) instead of `out`.
  CommandResult RunWithStdout(std::string_view tool, const std::vector<std::string>& args, const fs::path& stdout_to) const;

  // Runs calib-synth (DefaultSynthArgs() unless `args` is given) writing `relative` and its
  // truth file beside it; fails the test unless it succeeds. Returns the correspondences.
  Json Synth(const std::string& relative = "in/volume.json", std::vector<std::string> args = {}) const;

  // The error contract for a failing run: `exit_code`; nothing on stdout; stderr exactly one line
  // starting "<tool>: error: " and containing `location` (e.g. "in/bad.json: views[0].points[3]: ")
  // and every phrase.
  static ::testing::AssertionResult FailsWith(const CommandResult& result, std::string_view tool, int exit_code,
                                              const std::string& location, const std::vector<std::string>& phrases);

  // Names of the entries of a directory (relative to the test directory), sorted.
  std::vector<std::string> List(const std::string& relative) const;
  // out/ is empty: no output file and no stray temporary (".name.XXXXXX") was left behind.
  ::testing::AssertionResult OutDirEmpty() const;
  // `tool` run with `args` writes `outputs` (relative paths, each overwritten by the second run's):
  // run once, remove them, run again; success when both runs succeed with the same bytes in each.
  ::testing::AssertionResult SameBytesTwice(std::string_view tool, const std::vector<std::string>& args,
                                            const std::vector<std::string>& outputs) const;

 private:
  fs::path dir_;
};

}  // namespace vstcal::cli_test
