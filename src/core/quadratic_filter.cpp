#include "core/quadratic_filter.hpp"

#include <cstddef>

#include "core/separable_filter.hpp"

namespace lfcam {

std::vector<float> quadraticFitTaps(int radius) {
  const double r = radius, scale = (2 * r - 1) * (2 * r + 1) * (2 * r + 3);
  std::vector<float> taps(2 * std::size_t(radius) + 1);
  for (int k = -radius; k <= radius; ++k)
    taps[k + radius] = float((3 * (3 * r * r + 3 * r - 1) - 15.0 * k * k) / scale);
  return taps;
}

void quadraticFitFilter(const float* in, float* out, int width, int height, int radius) {
  separableFilter(in, out, width, height, quadraticFitTaps(radius));
}

}  // namespace lfcam
