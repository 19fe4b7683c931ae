// What every vstcal tool's main shares: CLI11 parsing with documented exit codes, exceptions
// turned into one-line messages (docs/conventions.md#exit-codes).
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace vstcal::tools {

// Adds --version, parses argv with `app`, then runs `body`. Returns the process exit code:
//  0 ok (also for --help and --version), 2 bad usage or input, 3 degenerate data, 1 internal error.
// Every failure prints exactly one line on stderr, "<tool>: error: <message>" (or "<tool>:
// internal error: … (please report this)" for exit code 1); control characters in the message
// are escaped so that it stays one line.
int RunTool(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

}  // namespace vstcal::tools
