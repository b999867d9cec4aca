// Weighted median of a window (edof_internal.hpp): the sorting reference of the selection
// (weighted_median_select.cpp), and the depth map's guided median.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "edof/edof_internal.hpp"
#include "lfcam/parallel.hpp"

namespace lfcam::edof {

float weightedMedianSorted(const float* values, const float* weights, std::size_t n, float total) {
  std::vector<std::pair<float, float>> window(n);
  for (std::size_t i = 0; i < n; ++i) window[i] = {values[i], weights[i]};
  std::sort(window.begin(), window.end());
  float running = 0;
  for (const auto& [value, weight] : window) {
    running += weight;
    if (running >= 0.5f * total) return value;
  }
  return window.back().first;
}

void guidedWeightedMedian(const Image& guide, int radius, float sigma, bool slanted, float* disparity) {
  const int ns = guide.width(), nt = guide.height(), channels = guide.channels();
  const std::vector<float> input(disparity, disparity + std::size_t(ns) * nt);
  const MapSlopes slopes = slanted ? mapSlopes(input.data(), ns, nt) : MapSlopes{};
  // The weights from a table of the squared colour distance in steps of 1/4096 (an exp per
  // neighbour would cost more than the selection); beyond 1 the weight is exp(-1 / (2 sigma^2)).
  constexpr int kSteps = 4096;
  std::vector<float> table(kSteps + 1);
  for (int i = 0; i <= kSteps; ++i) table[i] = std::exp(-(float(i) / kSteps) / (2 * sigma * sigma));
  std::vector<const float*> planes(channels);
  for (int c = 0; c < channels; ++c) planes[c] = guide.plane(c);
  const std::size_t side = 2 * std::size_t(std::max(radius, 0)) + 1;
  parallelFor(0, std::size_t(nt), 4, [&](std::size_t begin, std::size_t end) {
    std::vector<float> values(side * side + kMedianPadding), weights(side * side + kMedianPadding);
    for (std::size_t y = begin; y < end; ++y) {
      // The window clipped to the image, so that the loops below test no border.
      const int dyFirst = -std::min(radius, int(y)), dyLast = std::min(radius, nt - 1 - int(y));
      for (int x = 0; x < ns; ++x) {
        const int dxFirst = -std::min(radius, x), dxLast = std::min(radius, ns - 1 - x);
        const std::size_t p = y * ns + x;
        const float slopeX = slanted ? slopes.x[p] : 0.0f, slopeY = slanted ? slopes.y[p] : 0.0f;
        std::size_t n = 0;
        float total = 0;
        for (int dy = dyFirst; dy <= dyLast; ++dy) {
          const std::size_t row = std::size_t(long(y) + dy) * ns;
          for (int dx = dxFirst; dx <= dxLast; ++dx) {
            const std::size_t q = row + std::size_t(x + dx);
            float squares = 0;
            for (int c = 0; c < channels; ++c) {
              const float difference = planes[c][q] - planes[c][p];
              squares += difference * difference;
            }
            if (!(squares < 1.0f)) squares = 1.0f;  // also NaN
            const float weight = table[int(squares * kSteps + 0.5f)];
            values[n] = input[q] - slopeX * float(dx) - slopeY * float(dy);
            weights[n] = weight;
            total += weight;
            ++n;
          }
        }
        disparity[p] = weightedMedianSelect(values.data(), weights.data(), n, total);
      }
    }
  });
}

}  // namespace lfcam::edof
