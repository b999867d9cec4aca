// Convolution by the same odd-length taps along x, then along y, the image's edge pixels repeated
// beyond it: the Gaussian blur and the quadratic fit share it. Planes are row-major width x height
// float arrays.
#pragma once

#include <vector>

namespace lfcam {

// `out` may be `in`.
void separableFilter(const float* in, float* out, int width, int height, const std::vector<float>& taps);

}  // namespace lfcam
