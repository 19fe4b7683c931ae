// What every command of the application layer returns (docs/architecture.md): the files it writes,
// all or nothing, and the summary a tool prints on stderr. A tool's main only parses its flags into
// a request, calls the command and hands the Outcome to WriteOutcome.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace vstcal::app {

struct Outcome {
  std::vector<std::pair<std::filesystem::path, std::string>> files;  // path, bytes
  std::string summary;                                               // for stderr
  // Lines for stderr that a tool prints even when quiet, before it writes the files.
  std::vector<std::string> warnings;
  // What a tool prints on stdout after writing the files: a result that is text (reproj-report's
  // table, calib-compare, err-sim check); empty: nothing.
  std::string stdout_text;
  // A check the user asked for failed (calib-compare --max-px, err-sim check): the files are still
  // written and the text printed; the tool exits with ExitCode::kCheckFailed.
  bool check_failed = false;
  // The output folders the command is given as folders (calib-capture's --overlay and render's
  // -o): created when missing and their parent exists, removed again if writing fails. The folder
  // of every other output must exist, as for every tool (atomic_write.h).
  std::vector<std::filesystem::path> folders;
};

// Writes every file all-or-nothing (WriteFilesAtomically: no output may be an input, no two
// outputs one file).
void WriteOutcome(const Outcome& outcome);

// The tool's exit status once the outcome is written: ExitCode::kCheckFailed (4) when a check
// failed, else 0.
int ExitStatus(const Outcome& outcome);

}  // namespace vstcal::app
