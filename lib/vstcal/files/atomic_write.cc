#include "vstcal/files/atomic_write.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "vstcal/core/error.h"
#include "vstcal/files/input_protection.h"

namespace vstcal {

namespace {

// Writes `text` to a new temporary file beside `path`; returns the temporary's name.
std::string WriteTemporary(const std::filesystem::path& path, const std::string& text) {
  const std::string name = path.string();
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw InputError(name + ": cannot write: directory " + dir.string() + " does not exist; create it first");
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(name + ": cannot write: it is a directory; give a file name");
  }
  // Built by appending: GCC 12's -Wrestrict misfires on `"." + std::string`.
  std::string hidden(".");
  hidden.append(path.filename().string()).append(".XXXXXX");
  const std::string tmpl = (dir / hidden).string();
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  const int fd = mkstemp(buf.data());
  if (fd < 0) {
    throw InputError(name + ": cannot write (" + std::strerror(errno) + "); check the directory's permissions");
  }
  const std::string tmp(buf.data());
  size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      std::remove(tmp.c_str());
      throw InputError(name + ": write failed (" + std::strerror(err) + "); check free disk space");
    }
    written += static_cast<size_t>(n);
  }
  ::fchmod(fd, 0644);  // mkstemp creates 0600; outputs are ordinary files
  if (::close(fd) != 0) {
    const int err = errno;
    std::remove(tmp.c_str());
    throw InputError(name + ": write failed (" + std::strerror(err) + "); check free disk space");
  }
  return tmp;
}

}  // namespace

void WriteFilesAtomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files) {
  // Refuse before writing anything: an empty name, one file given for two outputs (the second
  // rename would silently replace the first output), an output that is an input of the run.
  std::vector<std::filesystem::path> paths;
  for (const auto& [path, text] : files) {
    if (path.empty()) throw InputError("an output file name is empty; give a file name");
    paths.push_back(path);
  }
  CheckOutputs(paths);
  std::vector<std::string> temporaries;
  try {
    for (const auto& [path, text] : files) temporaries.push_back(WriteTemporary(path, text));
  } catch (...) {
    for (const std::string& t : temporaries) std::remove(t.c_str());
    throw;
  }
  for (size_t i = 0; i < files.size(); ++i) {
    if (std::rename(temporaries[i].c_str(), files[i].first.c_str()) != 0) {
      const int err = errno;
      for (size_t k = i; k < files.size(); ++k) std::remove(temporaries[k].c_str());
      // Outputs already in place would be a partial set: remove them too.
      for (size_t k = 0; k < i; ++k) std::remove(files[k].first.c_str());
      throw InputError(files[i].first.string() + ": cannot write (" + std::strerror(err) + "); check the path");
    }
  }
}

void WriteFileAtomically(const std::filesystem::path& path, const std::string& text) {
  WriteFilesAtomically({{path, text}});
}

}  // namespace vstcal
