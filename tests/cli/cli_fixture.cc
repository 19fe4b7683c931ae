#include "cli_fixture.h"

#include <stdlib.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace vstcal::cli_test {

std::string ToolPath(std::string_view tool) {
  // VSTCAL_CLI_TOOLS_DIR runs the same tests against other builds of the tools (e.g. installed).
  const char* dir = std::getenv("VSTCAL_CLI_TOOLS_DIR");
  return std::string(dir != nullptr && *dir != '\0' ? dir : VSTCAL_TOOLS_DIR) + "/" + std::string(tool);
}

std::vector<std::string> DefaultSynthArgs() {
  return {"--image-size",    "640x480", "--fx",  "600", "--grid",     "5x4", "--spacing",         "100",
          "--near",          "0",       "--far", "400", "--interval", "200", "--camera-distance", "1500",
          "--no-test-points"};
}

std::vector<std::string> Override(std::vector<std::string> args, const std::string& flag, const std::string& value) {
  const auto it = std::find(args.begin(), args.end(), flag);
  if (it != args.end() && it + 1 != args.end()) {
    *(it + 1) = value;
  } else {
    args.push_back(flag);
    args.push_back(value);
  }
  return args;
}

std::vector<std::string> Remove(std::vector<std::string> args, const std::string& flag, bool has_value) {
  const auto it = std::find(args.begin(), args.end(), flag);
  if (it != args.end()) args.erase(it, it + (has_value ? 2 : 1));
  return args;
}

Pinhole Pinhole::FromTruth(const Json& truth) {
  Pinhole p;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      p.K(r, c) = truth.at("K").at(r).at(c).get<double>();
      p.R(r, c) = truth.at("camera_from_world").at("R").at(r).at(c).get<double>();
    }
    p.t(r) = truth.at("camera_from_world").at("t").at(r).get<double>();
  }
  return p;
}

Json Pinhole::Observe(const Eigen::Vector3d& point_in_world) const {
  const Eigen::Vector3d h = K * (R * point_in_world + t);
  return Json::array({point_in_world.x(), point_in_world.y(), point_in_world.z(), h.x() / h.z(), h.y() / h.z()});
}

std::string LineColumn(const std::string& text, size_t offset) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

void CliTest::SetUp() {
  const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  std::string safe;
  for (char c : name) safe += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  std::string tmpl = (fs::temp_directory_path() / ("vstcal-cli-" + safe.substr(0, 60) + "-XXXXXX")).string();
  ASSERT_NE(::mkdtemp(tmpl.data()), nullptr) << "cannot create a temporary directory from " << tmpl;
  dir_ = tmpl;
  fs::create_directory(dir_ / "in");
  fs::create_directory(dir_ / "out");
}

void CliTest::TearDown() {
  if (dir_.empty()) return;
  std::error_code ec;
  fs::remove_all(dir_, ec);
  EXPECT_FALSE(ec) << "cannot remove " << dir_ << ": " << ec.message();
}

void CliTest::WriteText(const std::string& relative, const std::string& text) const {
  std::ofstream out(Path(relative), std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + Path(relative).string());
}

std::string CliTest::ReadText(const std::string& relative) const {
  std::ifstream in(Path(relative), std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + Path(relative).string());
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

CommandResult CliTest::Run(std::string_view tool, const std::vector<std::string>& args) const {
  std::vector<std::string> argv = {ToolPath(tool)};
  argv.insert(argv.end(), args.begin(), args.end());
  return RunCommand(argv, dir_);
}

CommandResult CliTest::RunWithStdout(std::string_view tool, const std::vector<std::string>& args,
                                     const fs::path& stdout_to) const {
  std::vector<std::string> argv = {ToolPath(tool)};
  argv.insert(argv.end(), args.begin(), args.end());
  return RunCommand(argv, dir_, stdout_to);
}

Json CliTest::Synth(const std::string& relative, std::vector<std::string> args) const {
  if (args.empty()) args = DefaultSynthArgs();
  args.push_back("-o");
  args.push_back(relative);
  const CommandResult r = Run("calib-synth", args);
  EXPECT_EQ(r.exit_code, kOk) << "calib-synth failed to build the test input:\n" << r.err;
  if (r.exit_code != kOk) throw std::runtime_error("calib-synth failed: " + r.err);
  return ReadJson(relative);
}

std::string JUnitCounts(const fs::path& file) {
  const CommandResult r = RunCommand(
      {"/usr/bin/python3", "-c",
       "import sys, xml.etree.ElementTree as ET\n"
       "root = ET.parse(sys.argv[1]).getroot()\n"
       "assert root.tag == 'testsuites', root.tag\n"
       "suite = root.find('testsuite')\n"
       "cases = suite.findall('testcase')\n"
       "assert suite.get('tests') == str(len(cases))\n"
       "print(len(cases), suite.get('failures'), sum(len(c.findall('failure')) for c in cases))\n",
       file.string()});
  EXPECT_EQ(r.exit_code, 0) << file << ": " << r.err;
  return r.out;
}

::testing::AssertionResult CliTest::FailsWith(const CommandResult& r, std::string_view tool, int exit_code,
                                              const std::string& location, const std::vector<std::string>& phrases) {
  std::vector<std::string> problems;
  if (r.exit_code != exit_code) {
    problems.push_back("exit code " + std::to_string(r.exit_code) + ", expected " + std::to_string(exit_code));
  }
  if (!r.out.empty()) problems.push_back("stdout is not empty");
  if (r.err.empty() || r.err.back() != '\n') problems.push_back("stderr does not end with a newline");
  if (const auto lines = std::count(r.err.begin(), r.err.end(), '\n'); lines != 1) {
    problems.push_back("stderr has " + std::to_string(lines) + " lines, expected exactly 1");
  }
  const std::string prefix = std::string(tool) + ": error: ";
  if (r.err.rfind(prefix, 0) != 0) problems.push_back("stderr does not start with \"" + prefix + "\"");
  if (!location.empty() && r.err.find(location) == std::string::npos) {
    problems.push_back("stderr does not name the location \"" + location + "\"");
  }
  for (const std::string& phrase : phrases) {
    if (r.err.find(phrase) == std::string::npos) problems.push_back("stderr lacks \"" + phrase + "\"");
  }
  if (problems.empty()) return ::testing::AssertionSuccess();
  auto failure = ::testing::AssertionFailure();
  for (const std::string& p : problems) failure << p << "\n";
  return failure << "stdout: " << r.out << "\nstderr: " << r.err;
}

std::vector<std::string> CliTest::List(const std::string& relative) const {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(Path(relative))) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

::testing::AssertionResult CliTest::SameBytesTwice(std::string_view tool, const std::vector<std::string>& args,
                                                   const std::vector<std::string>& outputs) const {
  std::vector<std::string> first;
  for (int run = 0; run < 2; ++run) {
    const CommandResult r = Run(tool, args);
    if (r.exit_code != kOk) return ::testing::AssertionFailure() << "run " << run + 1 << " failed: " << r.err;
    for (size_t i = 0; i < outputs.size(); ++i) {
      const std::string text = ReadText(outputs[i]);
      if (run == 0) {
        first.push_back(text);
        fs::remove(Path(outputs[i]));
      } else if (text != first[i]) {
        return ::testing::AssertionFailure() << outputs[i] << " differs between two runs";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult CliTest::OutDirEmpty() const {
  const std::vector<std::string> names = List("out");
  if (names.empty()) return ::testing::AssertionSuccess();
  auto failure = ::testing::AssertionFailure() << "out/ should be empty after a failure, but holds:";
  for (const std::string& n : names) failure << " " << n;
  return failure;
}

}  // namespace vstcal::cli_test
