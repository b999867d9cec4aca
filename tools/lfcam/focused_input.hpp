// A focused plenoptic capture (plenoptic 2.0, Raytrix) given to a command that also takes light
// fields: recognised by its calibration beside it (same name, .xml) or named by
// --focused-calibration, or said to be one with --focused (calibrated from itself when no
// calibration is beside it), and the options every focused path shares.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "commands.hpp"
#include "lfcam/focused/focused_capture.hpp"

namespace lfcam::cli {

struct FocusedOptions {
  std::string calibration;
  bool focused = false;
  double pixelsPerLens = 0;  // 0: a quarter of the micro-image diameter
};

void addFocusedOptions(CLI::App& command, FocusedOptions& focused);

// Whether INPUT is a focused capture: --focused, a calibration named, or one beside it.
bool isFocusedInput(const InputOptions& input, const FocusedOptions& focused);
// Reads it (the --white of the input options devignettes it, and calibrates it with --focused
// and no calibration), with a progress-free read.
Result<FocusedCapture> loadFocusedInput(const InputOptions& input, const FocusedOptions& focused);
double pixelsPerLens(const FocusedOptions& focused, const FocusedCalibration& calibration);

}  // namespace lfcam::cli
