// A focused plenoptic capture calibrated without a calibration file: the micro-image lattice from
// a white image of the camera or from the capture itself (its micro-images' vignetting), which way
// up the micro-images stand, and the lens types from their sharpness (lens_types_from_sharpness.hpp).
#pragma once

#include <optional>
#include <string>

#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/focused/focused_calibration.hpp"

namespace lfcam {

struct FocusedSelfCalibrationOptions {
  // Otherwise the way under which the micro-images agree best (the higher mean confidence of
  // a coarse virtual-depth map, focused_depth.hpp).
  std::optional<MicroImageOrientation> orientation;
  double borderPx = 1;  // Raytrix's lens_border
};

struct FocusedSelfCalibration {
  FocusedCalibration calibration;
  GridFitReport gridFit;  // the lattice fit (calibrate.hpp), before it is made ideal
  // The mean confidence of the coarse depth map each way up (0 when the way was given).
  double confidenceUpright = 0, confidenceInverted = 0;
  double lensTypeSpread = 0;  // lens_types_from_sharpness.hpp
};

// `capture` in linear light (devignetted or not), any number of channels; `where` names it in
// errors. The lattice is found on `white` when one is given (every micro-image lit: sharper),
// otherwise on the capture. The lattice is made ideal (one diameter, no warp), as Raytrix's calibration is; its
// reference lens is the one nearest the image's centre.
Result<FocusedSelfCalibration> calibrateFocusedCapture(const Image& capture, const Image* white,
                                                       const FocusedSelfCalibrationOptions& options,
                                                       const std::string& where);

}  // namespace lfcam
