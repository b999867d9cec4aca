// Bilinear sampling of a plane, one sample at a time: the scalar reference of every module's
// sampler (depth's fine search, the focus search of a focal stack, the calibration's centre
// search) and of the fast row samplers tested against it.
#pragma once

#include <algorithm>
#include <cstddef>

namespace lfcam {

// The row-major plane of width x height floats at index position (x, y) (samples at whole
// numbers), the position clamped to the plane, so the border extends outwards.
inline float bilinearSample(const float* plane, int width, int height, double x, double y) {
  x = std::clamp(x, 0.0, double(width - 1));
  y = std::clamp(y, 0.0, double(height - 1));
  const int x0 = std::min(int(x), std::max(width - 2, 0)), y0 = std::min(int(y), std::max(height - 2, 0));
  const int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  const float fx = float(x - x0), fy = float(y - y0);
  const float* row0 = plane + std::size_t(y0) * width;
  const float* row1 = plane + std::size_t(y1) * width;
  const float top = row0[x0] + fx * (row0[x1] - row0[x0]), bottom = row1[x0] + fx * (row1[x1] - row1[x0]);
  return top + fy * (bottom - top);
}

}  // namespace lfcam
