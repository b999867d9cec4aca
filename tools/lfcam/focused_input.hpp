// A focused plenoptic capture (plenoptic 2.0, Raytrix) given to a command that also takes light
// fields: recognised by its calibration beside it (same name, .xml) or named by
// --focused-calibration, and the options every focused path shares.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "commands.hpp"
#include "lfcam/focused/focused_capture.hpp"

namespace lfcam::cli {

struct FocusedOptions {
  std::string calibration;
  double pixelsPerLens = 0;  // 0: a quarter of the micro-image diameter
};

void addFocusedOptions(CLI::App& command, FocusedOptions& focused);

// Whether INPUT is a focused capture: a calibration named, or one beside it.
bool isFocusedInput(const InputOptions& input, const FocusedOptions& focused);
// Reads it (the --white of the input options devignettes it), with a progress-free read.
Result<FocusedCapture> loadFocusedInput(const InputOptions& input, const FocusedOptions& focused);
double pixelsPerLens(const FocusedOptions& focused, const FocusedCalibration& calibration);

}  // namespace lfcam::cli
