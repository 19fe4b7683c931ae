// Inputs are never overwritten (docs/reliability.md#inputs). While an InputProtection exists — a
// tool's RunTool holds one for the whole run — every file a reader opens (ReadInputFile, or
// NoteInputFile for files read another way, such as images) is remembered by its identity
// (st_dev, st_ino), and outputs are checked against the inputs and against each other:
//  - an output that is an input, however it is spelled (a.json, ./a.json, a symlink to it, a hard
//    link: one st_dev and st_ino), is refused;
//  - two outputs that name one file are refused.
// WriteFilesAtomically checks its files before writing any, so no tool can break the rule. A tool
// that declares its outputs as soon as it has parsed its flags (DeclareOutputs) gets the refusal
// before any work: a reader then refuses an input that is a declared output.
// Without an InputProtection (library use, tests that read and rewrite one file) nothing is
// recorded and only the two-outputs rule applies. Thread-safe.
#pragma once

#include <filesystem>
#include <vector>

namespace vstcal {

class InputProtection {
 public:
  InputProtection();  // at most one at a time
  ~InputProtection();
  InputProtection(const InputProtection&) = delete;
  InputProtection& operator=(const InputProtection&) = delete;
};

// The files a run will write. Throws InputError when two of them are one file, or one of them is
// an input already read; later reads of any of them throw too. Empty paths are skipped.
void DeclareOutputs(const std::vector<std::filesystem::path>& outputs);

// Records a file as an input of the run (ReadInputFile calls it). Throws InputError when it is a
// declared output. Does nothing without an InputProtection.
void NoteInputFile(const std::filesystem::path& path);

// What a path names, for a reader to refuse anything but a regular file before it opens it: a
// device or a pipe (/dev/zero, a FIFO) has no size, may never end, and opening a FIFO blocks until
// something writes to it. Symlinks are followed. kUnknown: stat failed otherwise (e.g. permission
// denied), and opening the file will say why.
enum class PathKind { kRegularFile, kMissing, kDirectory, kSpecial, kUnknown };
PathKind KindOfPath(const std::filesystem::path& path);

// Throws InputError when two outputs are one file, or (with an InputProtection) when an output is
// an input read so far. WriteFilesAtomically calls it before writing anything.
void CheckOutputs(const std::vector<std::filesystem::path>& outputs);

}  // namespace vstcal
