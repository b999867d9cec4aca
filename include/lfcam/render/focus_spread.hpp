// Focus spread: a photograph with everything between a near and a far depth in focus, and the blur
// outside that range growing as a real lens's does (not a hard cut), from a light field and its
// disparity map (depth.hpp; the map of the aperture centre, pixels per view step).
//
// Each output pixel is refocused (refocus.hpp, full aperture, same weights and normalisation) at
// its own disparity clamped into [farSlope, nearSlope]: inside the range at its own depth, sharp;
// outside at the nearer end of the range, blurred by its distance from it exactly as a lens focused
// there would blur it. Rays that reach a pixel through a surface nearer than its own (more than
// kOccluderMargin nearer, in each view's disparity map forward-warped from the centre's) are left
// out, so a sharp near surface leaves no ghost of itself over the farther pixels beside it, which
// are rendered at another slope.
//
// Cost: one refocus, plus one forward warp of the disparity map per view (a float per view pixel).
#pragma once

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

// Disparity by which a surface must be nearer than a pixel's own to occlude its rays (px per view
// step): above the noise of an estimated map, below the steps between surfaces people separate.
constexpr double kOccluderMargin = 0.2;

// Usage errors: a disparity map of another size than the views (or not one channel, or not finite),
// or a range with its near end behind its far end (nearSlope < farSlope; slopes grow towards the
// camera). checkFocusSpread says so before any work.
Status checkFocusSpread(const LightField& lightField, const Image& disparity, double farSlope, double nearSlope);
Result<Image> refocusSpread(const LightField& lightField, const Image& disparity, double farSlope, double nearSlope);

}  // namespace lfcam
