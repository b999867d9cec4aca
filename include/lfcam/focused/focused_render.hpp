// Photographs from a focused plenoptic image (focused_calibration.hpp's geometry): each pixel of
// the photograph (photo_frame.hpp) is a point Q at virtual depth v, which the micro-image centred
// at C shows at S = C + orientation (Q - C) / v.
//
// - Lumsdaine and Georgiev's basic rendering (nearestLensOnly): one v for all, each pixel from
//   the micro-image whose centre is nearest: patches of D / v pixels tiled, which show seams
//   wherever the scene is not at v.
// - Blended rendering: every micro-image whose sampled disc holds S adds it, weighted smoothly to
//   zero at the disc's rim (no seams). The disc is the `aperture` share of the micro-image's usable
//   radius, moved by `viewpoint`: a smaller disc is a smaller synthetic aperture, a moved one a
//   moved viewpoint (the rays through one part of the main lens), and one v for the whole
//   photograph refocuses it there while other depths blur as through that aperture.
// - Depth-based ("total focus"): v from a map on the photograph's frame, so every pixel is in focus;
//   on a multi-focus array each lens type is weighted by its sharpness at that v (its defocus from
//   the middle of its range in 1/v), so the sharpest types dominate.
// Micro-images are sampled with Keys's cubic (a = -3/4) where a photograph pixel is about a sensor
// pixel wide (bilinear blurred detail the ideal keeps there), with bilinear where it is two or more
// (its low pass suits the wider footprint), and a blend between (docs/design.md).
#pragma once

#include <array>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/focused/focused_calibration.hpp"
#include "lfcam/focused/photo_frame.hpp"

namespace lfcam {

struct FocusedRenderRequest {
  double pixelsPerLens = 8;                // the photograph's frame (photo_frame.hpp)
  double virtualDepth = 4;                 // where the photograph is focused, without a map
  const Image* virtualDepthMap = nullptr;  // one channel on the frame: each pixel's own v
  bool nearestLensOnly = false;            // Lumsdaine and Georgiev's patches
  double aperture = 1;                     // the sampled disc's radius, share of the usable radius
  std::array<double, 2> viewpoint{0, 0};   // the disc's centre, shares of the usable radius (x right, y down)
  bool sharpLensTypes = true;              // multi-focus: types weighted by their sharpness at v
};

// `image`: the capture in linear light, any number of channels, calibration.imageWidth x
// imageHeight. Usage errors: an image of another size, a viewpoint and aperture that leave the
// micro-image, a virtual depth whose patches (basic rendering) would reach past the micro-images'
// usable part, or a map of another size than the frame.
Result<Image> renderFocused(const Image& image, const FocusedCalibration& calibration,
                            const FocusedRenderRequest& request);

// Total focus (`lfcam edof` of a focused capture): every pixel of the frame of pixelsPerLens at its
// own virtual depth, from `virtualDepthMap` or, when null, from the map estimated on that frame
// (focused_depth.hpp, its default request).
Result<Image> renderTotalFocus(const Image& image, const FocusedCalibration& calibration, double pixelsPerLens,
                               const Image* virtualDepthMap = nullptr);

}  // namespace lfcam
