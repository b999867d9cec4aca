// How sharp each micro-image of a focused plenoptic capture is: on a multi-focus array the lens
// types differ most in this, each sharpest over its own range of virtual depth.
#pragma once

#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/focused/focused_calibration.hpp"

namespace lfcam {

// Per micro-image (grid.columns x grid.rows, row-major): the mean squared Laplacian of its
// luminance over its variance, inside the usable disc (so that contrast does not count, only
// detail), or 0 where the disc leaves the image or holds no contrast.
std::vector<float> microImageSharpness(const Image& image, const FocusedCalibration& calibration);

}  // namespace lfcam
