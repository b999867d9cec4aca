// Keys's cubic convolution (1981), one sample at a time: decoding's Catmull-Rom (a = -1/2, exact
// on quadratics) and focused rendering's sharper a = -3/4 (which offsets part of the sensor
// pixel's own blur where a photograph pixel is about a sensor pixel).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace lfcam {

inline constexpr double kCatmullRom = -0.5;

// The weights of the taps at -1, 0, 1 and 2 for a sample at fraction f in [0, 1), parameter a.
inline void keysCubicWeights(double f, double a, float w[4]) {
  const double f2 = f * f, f3 = f2 * f;
  w[0] = float(a * f3 - 2 * a * f2 + a * f);
  w[1] = float((a + 2) * f3 - (a + 3) * f2 + 1.0);
  w[2] = float(-(a + 2) * f3 + (2 * a + 3) * f2 - a * f);
  w[3] = float(-a * f3 + a * f2);
}

// The row-major plane of width x height floats at index position (x, y) (samples at whole
// numbers), each tap's index clamped to the plane, so the border extends outwards.
inline float cubicSample(const float* plane, int width, int height, double x, double y, double a) {
  const double fx = std::floor(x), fy = std::floor(y);
  float wx[4], wy[4];
  keysCubicWeights(x - fx, a, wx);
  keysCubicWeights(y - fy, a, wy);
  // Far off the plane every tap is its nearest border pixel: the position saturates there.
  const int bx = int(std::clamp(fx, -2.0, double(width))), by = int(std::clamp(fy, -2.0, double(height)));
  int columns[4];
  for (int t = 0; t < 4; ++t) columns[t] = std::clamp(bx - 1 + t, 0, width - 1);
  float sum = 0;
  for (int t = 0; t < 4; ++t) {
    const float* row = plane + std::size_t(std::clamp(by - 1 + t, 0, height - 1)) * std::size_t(width);
    sum +=
        wy[t] * (wx[0] * row[columns[0]] + wx[1] * row[columns[1]] + wx[2] * row[columns[2]] + wx[3] * row[columns[3]]);
  }
  return sum;
}

}  // namespace lfcam
