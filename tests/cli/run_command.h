// Runs a program with an argv vector (no shell, so no quoting problems) and captures its stdout
// and stderr separately. Used by the CLI tests to drive the tools as a user would.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace vstcal::cli_test {

struct CommandResult {
  // The exit status; 128 + N when the program was killed by signal N, -1 when it could not start.
  int exit_code = -1;
  std::string out;  // everything written to stdout
  std::string err;  // everything written to stderr
};

// argv[0] is the program's path (not searched in PATH). The program runs in `cwd` when it is
// not empty, with stdin from /dev/null. With `stdout_to` (e.g. /dev/full), its stdout goes to that
// file instead of `out`. Throws std::runtime_error when it cannot be started.
CommandResult RunCommand(const std::vector<std::string>& argv, const std::filesystem::path& cwd = {},
                         const std::filesystem::path& stdout_to = {});

}  // namespace vstcal::cli_test
