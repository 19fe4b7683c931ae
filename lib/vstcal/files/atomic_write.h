// Writing output files so that a failing tool never leaves a partial output behind
// (docs/reliability.md#atomic-outputs), and never overwrites one of its inputs (input_protection.h).
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace vstcal {

// Writes text to `path` through a temporary file in the same directory and a rename, so the
// path either holds the complete new file or is untouched. Throws InputError when the directory
// does not exist or is not writable.
void WriteFileAtomically(const std::filesystem::path& path, const std::string& text);

// Writes several files all-or-nothing: every text goes to a temporary file first; only when all
// are written are they renamed into place, so a failure leaves none of the outputs behind (if a
// rename fails midway, the outputs already renamed are removed). Refuses, before writing, an
// empty name, one file named for two outputs, or an output that is an input (CheckOutputs,
// input_protection.h).
void WriteFilesAtomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

}  // namespace vstcal
