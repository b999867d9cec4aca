// The fast shift-and-add kernel of refocus.cpp, generalised for the synthetic camera
// (synthetic_camera.cpp): a weighted sum of views, each resampled bilinearly at one constant
// shift, normalised per output pixel by the weight of the taps that landed inside the view
// (times the light field's weight):
//
//   E(x, y) = sum_k w_k W_k(x + dx_k, y + dy_k) L_k(x + dx_k, y + dy_k) / sum_k w_k W_k(...)
//
// Internal to the library.
#pragma once

#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"

namespace lfcam {

struct ShiftAndAddTerm {
  int u = 0, v = 0;               // view indices
  double shiftX = 0, shiftY = 0;  // the view is sampled at (x + shiftX, y + shiftY), pixels
  float weight = 1;               // the aperture's weight of this term; terms of weight 0 are skipped
};

Image shiftAndAdd(const LightField& lightField, std::vector<ShiftAndAddTerm> terms);

}  // namespace lfcam
