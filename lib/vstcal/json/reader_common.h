// What the readers of every format share: loading the file, and the two shapes of a bad-input
// message (docs/formats.md#common), so that a mrcal or OpenCV file is reported like a JSON one:
//   "<file>: <field>: <what is wrong>; <how to fix it>"         a value
//   "<file>: line L, column C: <what is wrong>; <how to fix it>" the syntax
// Both throw InputError (exit code 2).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "vstcal/core/limits.h"

namespace vstcal {

// The whole file as bytes. `kind` completes "is a directory, not <kind>" (e.g. "a JSON file").
// Errors: no such file, a directory, a device or a pipe (refused before it is opened), cannot
// open, larger than `max_bytes` (a format's own limit, docs/reliability.md#limits).
std::string ReadInputFile(const std::filesystem::path& path, std::string_view kind,
                          size_t max_bytes = limits::kMaxInputFileBytes, std::string_view limit_name = "");

// True when the text holds only spaces, tabs and line breaks.
bool IsBlank(std::string_view text);

// 1-based "line L, column C" of a byte offset in a text (columns count bytes).
std::string LineColumn(std::string_view text, size_t offset);

// A value's problem, before it is tied to a file and a field.
struct FieldProblem {
  std::string reason;  // what is wrong
  std::string fix;     // how to fix it
};

// Why `v` cannot be an image side (`what`: "width" or "height"): it must be a whole number of
// pixels from 1 to limits::kMaxImageSide. nullopt when it can. Every format's reader applies it.
std::optional<FieldProblem> ImageSideProblem(double v, std::string_view what);

// An empty field names the top level.
[[noreturn]] void FailField(std::string_view file, std::string_view field, std::string_view reason,
                            std::string_view fix);
[[noreturn]] void FailSyntax(std::string_view file, std::string_view text, size_t offset, std::string_view reason,
                             std::string_view fix);

}  // namespace vstcal
