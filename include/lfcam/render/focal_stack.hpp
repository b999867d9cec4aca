// Focal stacks, refocus at a pixel (click-to-focus), and the conversions between slope, alpha
// and metric focus distance.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/render/synthetic_camera.hpp"

namespace lfcam {

// n values evenly spaced from first to last inclusive (n = 1: first alone).
std::vector<double> evenlySpaced(double first, double last, int n);
// "FIRST:LAST:COUNT" (count 1 to 100000) -> evenlySpaced; a Usage error naming `option` otherwise.
Result<std::vector<double>> parseEvenlySpaced(const std::string& text, const std::string& option);

// One photograph of `camera` per slope (the camera's own slope is replaced), handed to `sink` in
// order as it is made, so that a stack of any depth needs the memory of one photograph. Stops at
// the first error, the sink's included. `camera.beta` and the aperture apply to every slice.
Status renderFocalStack(const LightField& lightField, const std::vector<double>& slopes, const SyntheticCamera& camera,
                        const RenderOptions& options,
                        const std::function<Status(int index, double slope, Image&& photo)>& sink);

// The slope that brings image point (x, y) (pixels, as in image.hpp) into sharpest focus: the
// one at which the views agree best around it (least variance across the views of the samples
// that refocusing at that slope adds up, over a (2 radius + 1)^2 window), searched over
// `steps` slopes from minSlope to maxSlope and refined by a parabola through the best three.
// Defaults: the light field's disparity range when its metadata states one, else [-4, 4].
struct FocusSearch {
  std::optional<double> minSlope, maxSlope;
  int steps = 81;
  int radius = 3;
};
Result<double> slopeAtPixel(const LightField& lightField, double x, double y, const FocusSearch& search = {});

// Thin-lens conversions (needs Optics::focalLengthMm): the film plane at alpha F behind the main
// lens is conjugate to the object plane at focusDistanceMm in front of it,
// 1/f = 1/distance + 1/(alpha F). Usage errors when the focal length is unknown or the plane
// would lie at or beyond infinity.
Result<double> focusDistanceMmFromAlpha(const Optics& optics, double alpha);
Result<double> alphaFromFocusDistanceMm(const Optics& optics, double distanceMm);

}  // namespace lfcam
