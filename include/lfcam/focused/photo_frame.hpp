// FocusedPhotoFrame: the pixel grid of a photograph rendered from a focused plenoptic image. It is
// the image's own frame (FocusedCalibration's Q) scaled by pixelsPerLens / D, less a margin of half
// a micro-image on each side, where too few micro-images see a point.
#pragma once

#include <array>

#include "lfcam/focused/focused_calibration.hpp"

namespace lfcam {

struct FocusedPhotoFrame {
  std::array<double, 2> originPx{0, 0};  // the image point of photograph pixel (0, 0)'s corner
  double imagePxPerPixel = 1;            // D / pixelsPerLens
  int width = 0, height = 0;

  // The image point of photograph position (x, y) (pixel (x, y)'s centre is (x + 0.5, y + 0.5)).
  std::array<double, 2> imagePoint(double x, double y) const {
    return {originPx[0] + x * imagePxPerPixel, originPx[1] + y * imagePxPerPixel};
  }
};

// pixelsPerLens: the photograph's pixels per micro-image pitch (Lumsdaine and Georgiev's patch
// size M; a point at virtual depth v is resolved up to D / v).
FocusedPhotoFrame focusedPhotoFrame(const FocusedCalibration& calibration, double pixelsPerLens);

// The frame a photograph takes unless asked otherwise: a quarter of the micro-image diameter,
// rounded (about the finest a point at virtual depth 4, Raytrix's middle, resolves).
double defaultPixelsPerLens(const FocusedCalibration& calibration);

}  // namespace lfcam
