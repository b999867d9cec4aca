// Focus measures used by tests: how sharp a region of an image is.
#pragma once

#include "lfcam/core/image.hpp"

namespace lfcam::test {

// Variance of the 4-neighbour Laplacian of the channel mean over [x0, x1) x [y0, y1) (the
// window is kept one pixel inside the image).
inline double laplacianVariance(const Image& image, int x0, int y0, int x1, int y1) {
  auto luminance = [&](int x, int y) {
    double sum = 0;
    for (int c = 0; c < image.channels(); ++c) sum += image.at(x, y, c);
    return sum / image.channels();
  };
  double sum = 0, sumSquares = 0;
  long count = 0;
  for (int y = std::max(y0, 1); y < std::min(y1, image.height() - 1); ++y)
    for (int x = std::max(x0, 1); x < std::min(x1, image.width() - 1); ++x) {
      const double lap =
          luminance(x - 1, y) + luminance(x + 1, y) + luminance(x, y - 1) + luminance(x, y + 1) - 4 * luminance(x, y);
      sum += lap, sumSquares += lap * lap, ++count;
    }
  if (count == 0) return 0;
  const double mean = sum / count;
  return sumSquares / count - mean * mean;
}

}  // namespace lfcam::test
