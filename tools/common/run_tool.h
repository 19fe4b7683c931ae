// What every vstcal tool's main shares: CLI11 parsing with documented exit codes, exceptions
// turned into one-line messages (docs/conventions.md#exit-codes).
#pragma once

#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "vstcal/files/input_protection.h"

namespace vstcal::tools {

// Adds --version, parses argv with `app`, then runs `body` under an InputProtection: no file
// the body reads can be written by it (docs/reliability.md#inputs). A body should first declare
// its outputs, so that a clash is refused before any work:
//   return RunTool(app, argc, argv, [&] {
//     DeclareOutputs({output, residuals});  // empty names (an unused flag) are skipped
//     const Correspondences c = ReadCorrespondences(input);  // refused if it is an output
//     ...
//     WriteFilesAtomically({{output, ...}, {residuals, ...}});  // checked again
//   });
// Files read without ReadInputFile (images through OpenCV) are recorded with
// NoteInputFile(path) before they are read.
// Returns the process exit code:
//  0 ok (also for --help and --version), 2 bad usage or input, 3 degenerate data, 1 internal error
//  (or a broken installation, which says how to fix it);
//  a body returns 4 (ExitCode::kCheckFailed, app::ExitStatus) itself when a check it ran failed.
// Every failure prints exactly one line on stderr, "<tool>: error: <message>" (or "<tool>:
// internal error: … (please report this)" for a bug, an InternalError); control characters in the message
// are escaped so that it stays one line.
int RunTool(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

// The name a tool installed under several (`names`, the first its own) was run as: argv[0]'s file
// name when it is one of them, else the first.
std::string InvokedAs(int argc, char** argv, std::initializer_list<std::string> names);

// A library message, summary or warning as this command line's user reads it: the options it
// names (core/option_name.h) spelled as flags, "--tilt-deg". Every text a tool prints from the
// library goes through it (RunTool's errors do).
std::string ForUser(std::string_view text);

// Writes `text` to stdout now and throws InputError when it cannot be written (a full disk,
// > /dev/full): a tool that also writes files prints first, so that a lost table leaves no file.
// RunTool checks stdout again at the end, for text printed any other way.
void PrintToStdout(const std::string& text);

}  // namespace vstcal::tools
