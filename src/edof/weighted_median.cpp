// Weighted median of a window (edof_internal.hpp): the sorting reference and the selection used
// by the depth map's guided median, which is O(n) on average instead of O(n log n); and that
// guided median.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "edof/edof_internal.hpp"
#include "lfcam/parallel.hpp"

namespace lfcam::edof {

float weightedMedianSorted(std::vector<std::pair<float, float>>& window, float total) {
  std::sort(window.begin(), window.end());
  float running = 0;
  for (const auto& [value, weight] : window) {
    running += weight;
    if (running >= 0.5f * total) return value;
  }
  return window.back().first;
}

float weightedMedianSelect(std::vector<std::pair<float, float>>& window, float total) {
  const float half = 0.5f * total;
  std::size_t lo = 0, hi = window.size();
  double below = 0;  // weight of the values known to lie below [lo, hi)
  while (hi - lo > 1) {
    const float a = window[lo].first, b = window[(lo + hi) / 2].first, c = window[hi - 1].first;
    const float pivot = std::max(std::min(a, b), std::min(std::max(a, b), c));  // median of three
    // Three-way partition: [lo, lt) < pivot, [lt, gt) == pivot, [gt, hi) > pivot.
    std::size_t lt = lo, i = lo, gt = hi;
    double lessWeight = 0, equalWeight = 0;
    while (i < gt) {
      const float v = window[i].first;
      if (v < pivot) {
        lessWeight += window[i].second;
        std::swap(window[lt++], window[i++]);
      } else if (v > pivot) {
        std::swap(window[i], window[--gt]);
      } else {
        equalWeight += window[i].second;
        ++i;
      }
    }
    if (below + lessWeight >= half && lt > lo) {
      hi = lt;  // half the weight is reached below the pivot
    } else if (below + lessWeight + equalWeight >= half || gt == hi) {
      return pivot;
    } else {
      below += lessWeight + equalWeight;
      lo = gt;
    }
  }
  return window[lo].first;
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
  parallelFor(0, std::size_t(nt), 4, [&](std::size_t begin, std::size_t end) {
    std::vector<std::pair<float, float>> window;
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < ns; ++x) {
        const std::size_t p = y * ns + x;
        const float slopeX = slanted ? slopes.x[p] : 0.0f, slopeY = slanted ? slopes.y[p] : 0.0f;
        window.clear();
        float total = 0;
        for (int dy = -radius; dy <= radius; ++dy) {
          const long yy = long(y) + dy;
          if (yy < 0 || yy >= nt) continue;
          for (int dx = -radius; dx <= radius; ++dx) {
            const int xx = x + dx;
            if (xx < 0 || xx >= ns) continue;
            const std::size_t q = std::size_t(yy) * ns + xx;
            float squares = 0;
            for (int c = 0; c < channels; ++c) {
              const float difference = guide.plane(c)[q] - guide.plane(c)[p];
              squares += difference * difference;
            }
            if (!(squares < 1.0f)) squares = 1.0f;  // also NaN
            const float weight = table[int(squares * kSteps + 0.5f)];
            window.emplace_back(input[q] - slopeX * float(dx) - slopeY * float(dy), weight);
            total += weight;
          }
        }
        disparity[p] = weightedMedianSelect(window, total);
      }
  });
}

}  // namespace lfcam::edof
