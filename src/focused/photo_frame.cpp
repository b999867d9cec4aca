#include "lfcam/focused/photo_frame.hpp"

#include <algorithm>
#include <cmath>

namespace lfcam {

FocusedPhotoFrame focusedPhotoFrame(const FocusedCalibration& calibration, double pixelsPerLens) {
  FocusedPhotoFrame frame;
  const double d = calibration.diameterPx();
  frame.imagePxPerPixel = d / pixelsPerLens;
  frame.originPx = {0.5 * d, 0.5 * d};
  frame.width = std::max(0, int(std::floor((calibration.imageWidth - d) / frame.imagePxPerPixel)));
  frame.height = std::max(0, int(std::floor((calibration.imageHeight - d) / frame.imagePxPerPixel)));
  return frame;
}

double defaultPixelsPerLens(const FocusedCalibration& calibration) {
  return std::max(1.0, std::round(calibration.diameterPx() / 4));
}

}  // namespace lfcam
