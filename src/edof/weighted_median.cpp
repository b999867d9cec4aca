// Weighted median of a window (edof_internal.hpp): the sorting reference and the selection used
// by the depth map's guided median, which is O(n) on average instead of O(n log n); and that
// guided median.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/box_filter.hpp"
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

namespace {

// The map's local slope, for the slanted median: central differences of its box mean over
// (2 kSlopeRadius + 1)^2 pixels, measured where no jump of more than kSlopeJump px between
// 4-neighbours lies within kSlopeRadius + 1 pixels (there the mean mixes two surfaces). Beside a
// jump (and in the image's outermost pixels) a pixel takes the mean slope measured within
// kSlopeReach pixels on its own surface (disparity within kSlopeJump per pixel of distance, plus
// one): else the median is flat there, and at the far end of a slanted floor, or on the side of a
// column turning away, its window holds only the surface's inner part and takes its disparity
// (steep slants 2.65 % flat beside jumps, 1.13 % with the reach below). Slopes under
// kSlopeMin px per pixel along both axes count as none (on a plane facing the camera the slope of
// the map's noise only roughens it).
// Chosen on the development scenes, one setting after the other, by the mean BadPix(0.07) at 128
// and 256 px per view and the mean bumpiness at 128 (a plain median: 2.45 %, 3.56 %, 0.951):
//   jump 0.1, 0.15, 0.2 px (radius 2, no minimum, flat beside jumps): 2.41 and 3.55 %; 2.31 and
//     3.65; 2.43 at 128. Without the jump test every occlusion edge got a slope: 9.42 %;
//   radius 1 and 3 (jump 0.15): 2.34 and 2.34 % at 128;
//   minimum 0, 0.005, 0.01, 0.02 (jump 0.1): 2.41, 2.39, 2.38, 2.39 % and bumpiness 0.975, 0.953,
//     0.932, 0.921; at 256 px 3.54 % for 0.01, 3.56 % for 0.02;
//   reach 0 (flat beside jumps), 4, 5, 7, 9: 2.38, 2.18, 1.97, 1.93, 2.03 % at 128; 3.54, 3.51 and
//     3.50 % at 256 for 0, 5 and 7; bumpiness 0.932 and 0.841 for 0 and 7;
//   then minimum 0.005 (reach 7): 1.88 and 3.52 %, bumpiness 0.886.
constexpr int kSlopeRadius = 2;
constexpr float kSlopeJump = 0.1f;
constexpr float kSlopeMin = 0.01f;
constexpr int kSlopeReach = 7;

struct Slopes {
  std::vector<float> x, y;  // px per view step per pixel
};

Slopes mapSlopes(const float* disparity, int width, int height) {
  const std::size_t n = std::size_t(width) * height;
  Slopes measured{std::vector<float>(n, 0.0f), std::vector<float>(n, 0.0f)};
  std::vector<char> isMeasured(n, 0);
  std::vector<float> mean(n);
  boxFilter(disparity, mean.data(), width, height, kSlopeRadius);
  const std::vector<int> jumps = jumpDistance(disparity, width, height, kSlopeJump, kSlopeRadius + 1);
  for (int y = 1; y + 1 < height; ++y)
    for (int x = 1; x + 1 < width; ++x) {
      const std::size_t p = std::size_t(y) * width + x;
      if (jumps[p] <= kSlopeRadius + 1) continue;
      measured.x[p] = 0.5f * (mean[p + 1] - mean[p - 1]);
      measured.y[p] = 0.5f * (mean[p + width] - mean[p - width]);
      isMeasured[p] = 1;
    }
  Slopes slopes = measured;
  parallelFor(0, std::size_t(height), 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t p = y * width + x;
        if (!isMeasured[p]) {
          double sumX = 0, sumY = 0;
          int count = 0;
          for (int qy = std::max(int(y) - kSlopeReach, 0); qy <= std::min(int(y) + kSlopeReach, height - 1); ++qy)
            for (int qx = std::max(x - kSlopeReach, 0); qx <= std::min(x + kSlopeReach, width - 1); ++qx) {
              const std::size_t q = std::size_t(qy) * width + qx;
              const int distance = std::max(std::abs(qx - x), std::abs(qy - int(y)));
              if (isMeasured[q] && std::abs(disparity[q] - disparity[p]) <= kSlopeJump * float(distance + 1))
                sumX += measured.x[q], sumY += measured.y[q], ++count;
            }
          if (count > 0) slopes.x[p] = float(sumX / count), slopes.y[p] = float(sumY / count);
        }
        if (std::max(std::abs(slopes.x[p]), std::abs(slopes.y[p])) < kSlopeMin) slopes.x[p] = slopes.y[p] = 0;
      }
  });
  return slopes;
}

}  // namespace

void guidedWeightedMedian(const Image& guide, int radius, float sigma, bool slanted, float* disparity) {
  const int ns = guide.width(), nt = guide.height(), channels = guide.channels();
  const std::vector<float> input(disparity, disparity + std::size_t(ns) * nt);
  const Slopes slopes = slanted ? mapSlopes(input.data(), ns, nt) : Slopes{};
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
