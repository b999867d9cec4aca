#include "progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace lfcam::cli {
ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), start_(std::chrono::steady_clock::now()), enabled_(::isatty(2) == 1) {}

ProgressBar::~ProgressBar() {
  if (shown_) std::fprintf(stderr, "\r%-80s\r", "");
}

void ProgressBar::operator()(double fraction) {
  if (!enabled_) return;
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start_;
  if (!shown_ && elapsed < std::chrono::seconds(1)) return;
  const int percent = int(std::clamp(fraction, 0.0, 1.0) * 100.0);
  if (percent == lastPercent_) return;
  lastPercent_ = percent;
  shown_ = true;
  constexpr int width = 30;
  const int filled = percent * width / 100;
  char left[32] = "";
  if (percent > 0) {
    const int seconds = int(elapsed.count() * (100 - percent) / percent + 0.5);
    std::snprintf(left, sizeof left, ", %d:%02d left", seconds / 60, seconds % 60);
  }
  std::fprintf(stderr, "\r%s [%s%s] %3d%%%s ", label_.c_str(), std::string(filled, '#').c_str(),
               std::string(width - filled, '.').c_str(), percent, left);
  std::fflush(stderr);
}

}  // namespace lfcam::cli
