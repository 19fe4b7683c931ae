#include "vstcal/json/reader_common.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/files/input_protection.h"

namespace vstcal {

std::string ReadInputFile(const std::filesystem::path& path, std::string_view kind, size_t max_bytes,
                          std::string_view limit_name) {
  const std::string name = path.string();
  switch (KindOfPath(path)) {
    case PathKind::kMissing: throw InputError(name + ": no such file; check the path");
    case PathKind::kDirectory: throw InputError(name + ": is a directory, not " + std::string(kind) + "; give the file's path");
    case PathKind::kSpecial:
      throw InputError(name + ": is not a regular file (a device, a pipe or a socket), not " + std::string(kind) +
                       "; give the file itself");
    case PathKind::kRegularFile:
    case PathKind::kUnknown: break;
  }
  const std::string too_large = name + ": larger than the " + std::to_string(max_bytes >> 20) + " MiB vstcal reads" +
                                (limit_name.empty() ? std::string() : " as " + std::string(limit_name)) +
                                " (docs/reliability.md#limits); check that it is " + std::string(kind) + ", or split the data";
  // The size is checked before reading, and again while reading (the file may grow meanwhile).
  std::error_code ec;
  if (std::filesystem::file_size(path, ec) > max_bytes && !ec) throw InputError(too_large);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name + ": cannot open (" + std::strerror(errno) + "); check its permissions");
  NoteInputFile(path);
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<size_t>(in.gcount()));
    if (text.size() > max_bytes) throw InputError(too_large);
  }
  if (in.bad()) throw InputError(name + ": cannot read (" + std::strerror(errno) + "); check the file");
  return text;
}

bool IsBlank(std::string_view text) { return text.find_first_not_of(" \t\r\n") == std::string_view::npos; }

std::string LineColumn(std::string_view text, size_t offset) {
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

std::optional<FieldProblem> ImageSideProblem(double v, std::string_view what) {
  const std::string fix = "give the image " + std::string(what) + " in pixels, a whole number from 1 to " +
                          std::to_string(limits::kMaxImageSide);
  char got[40];
  std::snprintf(got, sizeof got, "%.17g", v);
  if (v != std::floor(v)) return FieldProblem{"expected an integer, got " + std::string(got), fix};
  if (v <= 0) return FieldProblem{"must be a positive integer, got " + std::string(got), fix};
  if (v > limits::kMaxImageSide) {
    return FieldProblem{std::string(got) + " px is more than the " + std::to_string(limits::kMaxImageSide) +
                            " px per side vstcal accepts",
                        fix};
  }
  return std::nullopt;
}

void FailField(std::string_view file, std::string_view field, std::string_view reason, std::string_view fix) {
  throw InputError(std::string(file) + ": " + (field.empty() ? std::string("(top level)") : std::string(field)) + ": " +
                   std::string(reason) + "; " + std::string(fix));
}

void FailSyntax(std::string_view file, std::string_view text, size_t offset, std::string_view reason,
                std::string_view fix) {
  throw InputError(std::string(file) + ": " + LineColumn(text, offset) + ": " + std::string(reason) + "; " +
                   std::string(fix));
}

}  // namespace vstcal
