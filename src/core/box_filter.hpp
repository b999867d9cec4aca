// The mean over a square window, clipped to the image: a small filter used by several modules
// (calibration's smoothing, depth's refinement, the all-in-focus energy). Planes are row-major
// width x height float arrays.
#pragma once

namespace lfcam {

// Mean over the (2 r + 1)^2 window clipped to the image, in O(1) per pixel. `in` and `out` must
// not overlap.
void boxFilter(const float* in, float* out, int width, int height, int radius);

}  // namespace lfcam
