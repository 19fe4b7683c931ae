#include "common/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace vstcal::tools {

ProgressBar::ProgressBar(std::string label, bool enabled)
    : label_(std::move(label)), terminal_(enabled && isatty(STDERR_FILENO) == 1), start_(std::chrono::steady_clock::now()), last_(start_) {}

ProgressBar::~ProgressBar() {
  if (shown_) std::fprintf(stderr, "\r%*s\r", static_cast<int>(label_.size() + 60), "");
}

void ProgressBar::Update(double fraction) {
  if (!terminal_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - start_ < std::chrono::seconds(1) || (shown_ && now - last_ < std::chrono::milliseconds(100))) return;
  last_ = now;
  shown_ = true;
  fraction = std::clamp(fraction, 0.0, 1.0);
  constexpr int kWidth = 40;
  const int filled = static_cast<int>(fraction * kWidth);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double left = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
  std::fprintf(stderr, "\r%s [%s%s] %3d%% %4.0fs left", label_.c_str(), std::string(filled, '#').c_str(),
               std::string(kWidth - filled, ' ').c_str(), static_cast<int>(100 * fraction), left);
  std::fflush(stderr);
}

}  // namespace vstcal::tools
