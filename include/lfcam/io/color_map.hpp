// Colour maps for people to look at scalar maps (disparity, confidence).
//
// Turbo (Mikhailov 2019, Google): a perceptually smoothed rainbow, computed from its published
// polynomial approximation (sRGB-encoded values, converted here to the linear light that lfcam
// images hold, so that writeImage encodes them back exactly).
#pragma once

#include "lfcam/core/image.hpp"

namespace lfcam {

// Linear RGB of Turbo at x in [0, 1] (clamped): dark blue at 0, green-yellow in the middle,
// dark red at 1.
void turbo(double x, float rgb[3]);

// An RGB image of the first channel of `scalar` mapped linearly from [low, high] to Turbo;
// non-finite values are black. With low >= high the map's own finite range is used.
Image colorMap(const Image& scalar, double low = 0, double high = 0);

}  // namespace lfcam
