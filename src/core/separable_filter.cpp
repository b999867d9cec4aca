#include "core/separable_filter.hpp"

#include <algorithm>
#include <cstddef>

namespace lfcam {

void separableFilter(const float* in, float* out, int width, int height, const std::vector<float>& taps) {
  const int radius = int(taps.size() / 2);
  std::vector<float> across(std::size_t(width) * height);
  for (int y = 0; y < height; ++y) {
    const float* row = in + std::size_t(y) * width;
    for (int x = 0; x < width; ++x) {
      float sum = 0;
      for (int k = -radius; k <= radius; ++k) sum += taps[k + radius] * row[std::clamp(x + k, 0, width - 1)];
      across[std::size_t(y) * width + x] = sum;
    }
  }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float sum = 0;
      for (int k = -radius; k <= radius; ++k)
        sum += taps[k + radius] * across[std::size_t(std::clamp(y + k, 0, height - 1)) * width + x];
      out[std::size_t(y) * width + x] = sum;
    }
}

}  // namespace lfcam
