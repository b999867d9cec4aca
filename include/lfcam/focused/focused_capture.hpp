// A focused plenoptic capture as lfcam keeps it: the image of micro-images itself, demosaiced and
// devignetted, with its calibration (focused_calibration.hpp), rather than resampled into
// L(u, v, s, t): every photograph is rendered from the micro-images directly (docs/design.md).
#pragma once

#include <filesystem>
#include <optional>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/focused/focused_calibration.hpp"
#include "lfcam/focused/focused_self_calibration.hpp"

namespace lfcam {

struct FocusedCapture {
  Image image;  // linear, RGB (or one channel), the capture's size
  FocusedCalibration calibration;
  std::filesystem::path calibrationPath;  // empty when calibrated from itself
  // How, when calibrated from itself (focused_self_calibration.hpp).
  std::optional<FocusedSelfCalibration> selfCalibration;
};

struct FocusedCaptureOptions {
  std::filesystem::path calibration;  // empty: the one beside the capture (focusedCalibrationBeside)
  std::filesystem::path white;        // a white image of the same camera: the capture is divided by it
  // With no calibration named or beside it: calibrate it from the white image when given, else
  // from itself (its micro-images' vignetting), rather than fail.
  bool calibrateIfNone = false;
};

// The calibration a focused capture carries beside it: the same name with .xml (Raytrix's way);
// nothing when there is none. (A JSON calibration is named: a .json beside an image is often
// something else, a Lytro or simulator metadata file.)
std::optional<std::filesystem::path> focusedCalibrationBeside(const std::filesystem::path& capture);

// An RGB image is taken as demosaiced already (8 or 16 bit, its codes over their full scale); a
// one-channel one is a raw mosaic (readRaw: levels and Bayer pattern from the file or the
// simulator's camera.json), demosaiced. With a white image, each pixel is divided by the white's
// (normalised to its brightest), and pixels where the white is below 5 % of that are set to 0.
// Errors name the file: no calibration (none beside, none given, none to be found in it), or one
// of another image.
Result<FocusedCapture> readFocusedCapture(const std::filesystem::path& path, const FocusedCaptureOptions& options = {});

}  // namespace lfcam
