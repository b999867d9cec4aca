// experiments: the paper's measurements (sections 4.2 and 6, Figures 2, 6, 10, 11, 12) run on
// lfcam's own simulator and pipeline, each writing a report folder:
//   report.md, report.html   setup, numbers, the paper's numbers beside them
//   *.svg, *.png             plots and photographs, made by lfcam
//   *.csv                    the tables
//   results.json             headline numbers under stable keys (docs/formats.md)
// Every number comes from captures made here (no stored results). `quick` runs each in seconds
// at reduced size (for tests); the full run makes the figures of the README.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

struct ExperimentOptions {
  bool quick = false;
  ProgressCallback progress;
};

// "refocus-limit", "snr", "sharpness-vs-n", "fnumber-match", "observer-range".
std::vector<std::string> experimentNames();

// Runs experiment `name` and writes its report into `folder` (atomically: every file appears
// whole). Usage error for an unknown name.
Status runExperiment(const std::string& name, const std::filesystem::path& folder, const ExperimentOptions& options);

}  // namespace lfcam
