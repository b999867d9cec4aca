#include "core/quadratic_filter.hpp"

#include <algorithm>
#include <cstddef>

namespace lfcam {

std::vector<float> quadraticFitTaps(int radius) {
  const double r = radius, scale = (2 * r - 1) * (2 * r + 1) * (2 * r + 3);
  std::vector<float> taps(2 * std::size_t(radius) + 1);
  for (int k = -radius; k <= radius; ++k)
    taps[k + radius] = float((3 * (3 * r * r + 3 * r - 1) - 15.0 * k * k) / scale);
  return taps;
}

void quadraticFitFilter(const float* in, float* out, int width, int height, int radius) {
  const std::vector<float> taps = quadraticFitTaps(radius);
  std::vector<float> horizontal(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float sum = 0;
      for (int k = -radius; k <= radius; ++k)
        sum += taps[k + radius] * in[std::size_t(y) * width + std::clamp(x + k, 0, width - 1)];
      horizontal[std::size_t(y) * width + x] = sum;
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float sum = 0;
      for (int k = -radius; k <= radius; ++k)
        sum += taps[k + radius] * horizontal[std::size_t(std::clamp(y + k, 0, height - 1)) * width + x];
      out[std::size_t(y) * width + x] = sum;
    }
}

}  // namespace lfcam
