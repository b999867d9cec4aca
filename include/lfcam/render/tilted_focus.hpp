// Tilted focus (the Scheimpflug principle after the fact): a photograph focused on a plane of the
// scene that need not face the camera. A plane in the scene is, to first order, a plane in
// (x, y, slope): each output pixel is refocused (refocus.hpp, full aperture, same weights and
// normalisation) at its own slope
//
//   slope(x, y) = slope + gradientX (x - centreX) + gradientY (y - centreY)
//
// in pixels per view step, with (x, y) in image coordinates (image.hpp; pixel (i, j) is taken at its
// centre (i + 0.5, j + 0.5)). A plane of gradient 0 is refocus's fronto-parallel plane, pixel for
// pixel.
//
// The plane is given by three image points, each brought to its sharpest focus (slopeAtPixel,
// focal_stack.hpp), or by the slope at the image centre, a tilt (the change of slope over one image
// width) and the direction in which the slope grows.
//
// refocusTilted is the fast kernel (float32, views outer, threaded over blocks of rows), tested
// against a plain float64 per-pixel oracle (src/render/references.hpp).
#pragma once

#include <array>
#include <string>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/render/focal_stack.hpp"

namespace lfcam {

struct FocusPlane {
  double slope = 0;                     // at (centreX, centreY)
  double gradientX = 0, gradientY = 0;  // slope per pixel
  double centreX = 0, centreY = 0;      // image coordinates
  double slopeAt(double x, double y) const { return slope + gradientX * (x - centreX) + gradientY * (y - centreY); }
};

using ImagePoint = std::array<double, 2>;  // (x, y), image coordinates

// "X1,Y1:X2,Y2:X3,Y3" -> three points (the command line's --focus-plane, the viewer's plane=).
// Usage error for anything but six finite numbers so written.
Result<std::array<ImagePoint, 3>> parseFocusPlanePoints(const std::string& text);

// Whether three points can define a plane of focus, checked before any (slow) focus search. Usage
// errors: a point outside the image, or three points on (within a pixel of) one line.
Status checkFocusPlanePoints(const LightField& lightField, const std::array<ImagePoint, 3>& points);

// The plane through three image points at the slopes that focus each sharpest. Usage errors: those
// of checkFocusPlanePoints.
Result<FocusPlane> focusPlaneThroughPoints(const LightField& lightField, const std::array<ImagePoint, 3>& points,
                                           const FocusSearch& search = {});

// The plane through the plane of `slope` at the image centre, tilted so that the slope changes by
// `tilt` over one image width (ns pixels) towards `directionDeg` (0: to the right, 90: down).
FocusPlane focusPlaneFromTilt(const LightField& lightField, double slope, double tilt, double directionDeg);

// The photograph focused on `plane` (size and channels of the views).
Image refocusTilted(const LightField& lightField, const FocusPlane& plane);

}  // namespace lfcam
