#include "vstcal/json/reader_common.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "vstcal/core/error.h"

namespace vstcal::io {

std::string ReadInputFile(const std::filesystem::path& path, std::string_view kind) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(name + ": no such file; check the path");
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(name + ": is a directory, not " + std::string(kind) + "; give the file's path");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name + ": cannot open (" + std::strerror(errno) + "); check its permissions");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
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

std::string MessageNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
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

}  // namespace vstcal::io
