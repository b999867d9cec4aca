// Weighted median of a window (edof_internal.hpp): the sorting reference and the selection used
// by the depth map's guided median, which is O(n) on average instead of O(n log n).
#include <algorithm>
#include <utility>
#include <vector>

#include "edof/edof_internal.hpp"

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

}  // namespace lfcam::edof
