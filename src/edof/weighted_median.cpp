// Weighted median of a window (edof_internal.hpp): the sorting reference of the selection
// (weighted_median_select.cpp), and the depth map's guided median, its row kernel in
// guided_median_row.cpp and its reference.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/parallel.hpp"
#include "edof/edof_internal.hpp"

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

// The weights from a table of the squared colour distance in steps of 1/4096 (an exp per
// neighbour would cost more than the selection); beyond 1 the weight is exp(-1 / (2 sigma^2)).
constexpr int kSteps = 4096;

std::vector<float> weightTable(float sigma) {
  std::vector<float> table(kSteps + 1);
  for (int i = 0; i <= kSteps; ++i) table[i] = std::exp(-(float(i) / kSteps) / (2 * sigma * sigma));
  return table;
}

// `values` followed by kMedianPadding zeros.
std::vector<float> padded(const float* values, std::size_t n) {
  std::vector<float> copy(n + kMedianPadding, 0.0f);
  std::copy(values, values + n, copy.begin());
  return copy;
}

}  // namespace

void guidedWeightedMedian(const Image& guide, int radius, float sigma, bool slanted, float* disparity) {
  const int ns = guide.width(), nt = guide.height();
  const std::size_t n = std::size_t(ns) * nt;
  const std::vector<float> input = padded(disparity, n), table = weightTable(sigma);
  const MapSlopes slopes = slanted ? mapSlopes(input.data(), ns, nt) : MapSlopes{};
  std::vector<std::vector<float>> planes;
  GuidedMedianInputs inputs{.disparity = input.data(),
                            .slopeX = slanted ? slopes.x.data() : nullptr,
                            .slopeY = slanted ? slopes.y.data() : nullptr,
                            .table = table.data(),
                            .steps = kSteps,
                            .width = ns,
                            .height = nt,
                            .radius = std::max(radius, 0)};
  for (int c = 0; c < guide.channels(); ++c)
    inputs.planes.push_back(planes.emplace_back(padded(guide.plane(c), n)).data());
  const std::size_t side = 2 * std::size_t(inputs.radius) + 1;
  parallelFor(0, std::size_t(nt), 4, [&](std::size_t begin, std::size_t end) {
    std::vector<float> values(side * side + kMedianPadding), weights(side * side + kMedianPadding);
    for (std::size_t y = begin; y < end; ++y)
      guidedMedianRow(inputs, int(y), values.data(), weights.data(), disparity + y * ns);
  });
}

void guidedWeightedMedianReference(const Image& guide, int radius, float sigma, bool slanted, float* disparity) {
  const int ns = guide.width(), nt = guide.height(), channels = guide.channels();
  const std::vector<float> input(disparity, disparity + std::size_t(ns) * nt), table = weightTable(sigma);
  const MapSlopes slopes = slanted ? mapSlopes(input.data(), ns, nt) : MapSlopes{};
  std::vector<float> values, weights;
  for (int y = 0; y < nt; ++y)
    for (int x = 0; x < ns; ++x) {
      const std::size_t p = std::size_t(y) * ns + x;
      const float slopeX = slanted ? slopes.x[p] : 0.0f, slopeY = slanted ? slopes.y[p] : 0.0f;
      values.clear(), weights.clear();
      float total = 0;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          if (x + dx < 0 || y + dy < 0 || x + dx >= ns || y + dy >= nt) continue;
          const std::size_t q = std::size_t(y + dy) * ns + (x + dx);
          float squares = 0;
          for (int c = 0; c < channels; ++c) {
            const float difference = guide.plane(c)[q] - guide.plane(c)[p];
            squares += difference * difference;
          }
          if (!(squares < 1.0f)) squares = 1.0f;  // also NaN
          values.push_back(input[q] - slopeX * float(dx) - slopeY * float(dy));
          weights.push_back(table[int(squares * kSteps + 0.5f)]);
          total += weights.back();
        }
      disparity[p] = weightedMedianSorted(values.data(), weights.data(), values.size(), total);
    }
}

}  // namespace lfcam::edof
