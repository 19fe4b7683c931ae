// A progress bar on stderr for long runs: shown only when stderr is a terminal and the run has
// lasted more than a second, redrawn at most 10 times a second, erased when done.
#pragma once

#include <chrono>
#include <string>

namespace vstcal::tools {

class ProgressBar {
 public:
  // `enabled` false (e.g. --quiet) never draws.
  explicit ProgressBar(std::string label, bool enabled = true);
  ~ProgressBar();
  void Update(double fraction);  // 0…1

 private:
  std::string label_;
  bool terminal_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace vstcal::tools
