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

namespace {

// Keeps, in order, the entries whose value `keep` accepts; returns how many. Branch-free: the
// comparisons of a median's window are as good as random, and a mispredicted branch per entry
// cost more than the selection's arithmetic.
template <class Keep>
std::size_t compact(float* values, float* weights, std::size_t n, Keep keep) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float value = values[i], weight = weights[i];
    values[kept] = value;
    weights[kept] = weight;
    kept += keep(value) ? 1 : 0;
  }
  return kept;
}

}  // namespace

float weightedMedianSelect(float* values, float* weights, std::size_t n, float total) {
  const float half = 0.5f * total;
  double below = 0;  // weight of the values already known to lie below the window
  while (n > 1) {
    const float a = values[0], b = values[n / 2], c = values[n - 1];
    const float pivot = std::max(std::min(a, b), std::min(std::max(a, b), c));  // median of three
    // The weight below and at the pivot, in four sums so that the additions overlap. A value
    // neither below nor above (a NaN) counts as equal, so a NaN pivot ends the search.
    double less[4] = {}, equal[4] = {};
    std::size_t lessCount = 0, greaterCount = 0;
    const auto tally = [&](std::size_t i, double& lessSum, double& equalSum) {
      const float value = values[i], weight = weights[i];
      const bool isLess = value<pivot, isGreater = value> pivot;
      lessSum += weight * float(isLess);
      equalSum += weight * float(!isLess && !isGreater);
      lessCount += isLess;
      greaterCount += isGreater;
    };
    std::size_t i = 0;
    for (; i + 4 <= n; i += 4) {
      tally(i, less[0], equal[0]);
      tally(i + 1, less[1], equal[1]);
      tally(i + 2, less[2], equal[2]);
      tally(i + 3, less[3], equal[3]);
    }
    for (; i < n; ++i) tally(i, less[0], equal[0]);
    const double lessWeight = (less[0] + less[1]) + (less[2] + less[3]);
    const double equalWeight = (equal[0] + equal[1]) + (equal[2] + equal[3]);
    if (below + lessWeight >= half && lessCount > 0) {
      n = compact(values, weights, n, [pivot](float v) { return v < pivot; });  // half is reached below
    } else if (below + lessWeight + equalWeight >= half || greaterCount == 0) {
      return pivot;
    } else {
      below += lessWeight + equalWeight;
      n = compact(values, weights, n, [pivot](float v) { return v > pivot; });
    }
  }
  return values[0];
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
    std::vector<float> values(side * side), weights(side * side);
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
