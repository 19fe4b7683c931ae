#include "vstcal/pages/gnuplot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "vstcal/core/error.h"

extern char** environ;

namespace vstcal {
namespace {

// A file created by mkstemp in the temporary directory, removed when it goes out of scope.
class TempFile {
 public:
  explicit TempFile(const char* stem) {
    path_ = (std::filesystem::temp_directory_path() / (std::string(stem) + ".XXXXXX")).string();
    fd_ = mkstemp(path_.data());
    if (fd_ < 0) throw InternalError("cannot create a temporary file in " + std::filesystem::temp_directory_path().string());
  }
  ~TempFile() {
    if (fd_ >= 0) close(fd_);
    std::remove(path_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  int fd() const { return fd_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

bool GnuplotOnPath() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && access((dir + "/gnuplot").c_str(), X_OK) == 0) return true;
  }
  return false;
}

}  // namespace

std::string GnuplotQuoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '\\' || c == '"') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string RunGnuplot(const std::string& script) {
  VSTCAL_CHECK(script.size() <= kMaxGnuplotScriptBytes, "gnuplot script within its bound");
  if (!GnuplotOnPath()) throw InputError("gnuplot: not found on PATH; install gnuplot-nox (scripts/setup) to draw the charts");
  TempFile script_file("vstcal-plot"), errors("vstcal-plot-err");
  if (write(script_file.fd(), script.data(), script.size()) != static_cast<ssize_t>(script.size())) {
    throw InternalError("cannot write the gnuplot script to " + script_file.path());
  }
  int out[2];
  if (pipe(out) != 0) throw InternalError("pipe failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, errors.fd(), 2);
  posix_spawn_file_actions_addclose(&actions, out[0]);
  const std::string arg0 = "gnuplot";
  char* argv[] = {const_cast<char*>(arg0.c_str()), const_cast<char*>(script_file.path().c_str()), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);
  if (spawned != 0) {
    close(out[0]);
    throw InputError("gnuplot: cannot run it; install gnuplot-nox (scripts/setup) to draw the charts");
  }
  std::string svg;
  char buffer[1 << 16];
  bool too_long = false;
  for (ssize_t n; (n = read(out[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (svg.size() + static_cast<size_t>(n) > kMaxGnuplotOutputBytes) {
      too_long = true;
      kill(pid, SIGKILL);
      break;
    }
    svg.append(buffer, static_cast<size_t>(n));
  }
  close(out[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  VSTCAL_CHECK(!too_long, "gnuplot's output within its bound");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::ifstream in(errors.path());
    std::string line, first;
    while (std::getline(in, line)) {
      if (line.find_first_not_of(" \t^") != std::string::npos) first = line;  // the last message line
    }
    throw InternalError("gnuplot failed: " + first);
  }
  return svg;
}

std::string SvgChartHeader(int width, int height) {
  return "set terminal svg size " + std::to_string(width) + "," + std::to_string(height) +
         " font \"sans,11\" background \"white\"\nset output\nset grid lc rgb \"#dddddd\"\nset key below\n";
}

const char* ChartColour(size_t k) {
  static constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  return kColours[k % std::size(kColours)];
}

}  // namespace vstcal
