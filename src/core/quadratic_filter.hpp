// The value at each pixel of the quadratic that best fits (least squares) its (2 r + 1)^2
// neighbourhood (a Savitzky-Golay filter): a local mean that keeps curvature, where the box mean
// of a curved surface sags towards its concave side by about r(r + 1)/6 times the curvature per
// axis. Planes are row-major width x height float arrays.
#pragma once

#include <vector>

namespace lfcam {

// The filter's taps along one axis, from -r to r: (3 (3 r^2 + 3 r - 1) - 15 k^2) / ((2 r - 1)(2 r + 1)(2 r + 3)).
std::vector<float> quadraticFitTaps(int radius);

// Separable: the taps along x, then along y (the fit of a product of quadratics in x and y, exact
// on every quadratic surface). The image's edge pixels are repeated beyond it.
void quadraticFitFilter(const float* in, float* out, int width, int height, int radius);

}  // namespace lfcam
