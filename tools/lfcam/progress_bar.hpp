// A progress bar on stderr for work that takes over a second. Silent until then, and silent when
// stderr is not a terminal (logs and tests get no carriage-return noise). Shows the time left,
// extrapolated from the time so far.
#pragma once

#include <chrono>
#include <string>

namespace lfcam::cli {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();  // ends the line if the bar was shown
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void operator()(double fraction);

 private:
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  bool enabled_;
  bool shown_ = false;
  int lastPercent_ = -1;
};

}  // namespace lfcam::cli
