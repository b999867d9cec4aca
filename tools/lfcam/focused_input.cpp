#include "focused_input.hpp"

#include "lfcam/focused/photo_frame.hpp"

namespace lfcam::cli {

void addFocusedOptions(CLI::App& command, FocusedOptions& focused) {
  command.add_option("--focused-calibration", focused.calibration,
                     "INPUT is a focused plenoptic capture with this calibration (Raytrix .xml or .json); "
                     "default: INPUT's name with .xml, when it exists");
  command.add_flag("--focused", focused.focused,
                   "INPUT is a focused plenoptic capture: with no calibration beside it or named, calibrate it "
                   "from --white or from itself");
  command
      .add_option("--pixels-per-lens", focused.pixelsPerLens,
                  "focused captures: the photograph's pixels per micro-image (default: a quarter of its diameter)")
      ->check(CLI::PositiveNumber);
}

bool isFocusedInput(const InputOptions& input, const FocusedOptions& focused) {
  return focused.focused || !focused.calibration.empty() || focusedCalibrationBeside(input.path).has_value();
}

Result<FocusedCapture> loadFocusedInput(const InputOptions& input, const FocusedOptions& focused) {
  if (!input.dark.empty() || !input.grid.empty() || !input.whites.empty() || input.blackLevel)
    return makeError(ErrorCode::Usage, input.path +
                                           ": a focused plenoptic capture takes --white, not --dark, "
                                           "--grid, --whites or --black-level");
  return readFocusedCapture(
      input.path, {.calibration = focused.calibration, .white = input.white, .calibrateIfNone = focused.focused});
}

double pixelsPerLens(const FocusedOptions& focused, const FocusedCalibration& calibration) {
  return focused.pixelsPerLens > 0 ? focused.pixelsPerLens : defaultPixelsPerLens(calibration);
}

}  // namespace lfcam::cli
