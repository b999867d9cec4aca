// The weighted median by selection (src/edof/weighted_median.cpp) against the sorting reference,
// on random windows with ties, zero weights and the sizes the depth map's median uses.
#include <gtest/gtest.h>

#include <random>
#include <utility>
#include <vector>

#include "edof/edof_internal.hpp"

namespace lfcam::edof {
namespace {

TEST(WeightedMedian, SelectionAgreesWithTheSortingReference) {
  std::mt19937 random(6);
  std::uniform_real_distribution<float> value(-3.0f, 3.0f), weight(0.0f, 1.0f);
  std::uniform_int_distribution<int> size(1, 200), coin(0, 3);
  for (int trial = 0; trial < 5000; ++trial) {
    const int n = trial < 4 ? trial + 1 : size(random);
    std::vector<std::pair<float, float>> window(n);
    for (auto& [v, w] : window) {
      // A quarter of the values from a few levels (ties), some weights zero (the guide's table
      // underflows for very unlike neighbours).
      v = coin(random) == 0 ? float(coin(random)) : value(random);
      w = coin(random) == 0 ? 0.0f : weight(random);
    }
    window[0].second = 1.0f;  // the centre pixel always counts fully
    float total = 0;
    for (const auto& entry : window) total += entry.second;
    std::vector<std::pair<float, float>> copy = window;
    const float expected = weightedMedianSorted(window, total);
    ASSERT_EQ(weightedMedianSelect(copy, total), expected) << "trial " << trial << ", " << n << " values";
  }
}

TEST(WeightedMedian, HeavyWeightWins) {
  std::vector<std::pair<float, float>> window = {{5.0f, 0.1f}, {1.0f, 0.1f}, {3.0f, 10.0f}, {2.0f, 0.1f}};
  EXPECT_EQ(weightedMedianSelect(window, 10.3f), 3.0f);
  std::vector<std::pair<float, float>> even = {{1.0f, 1.0f}, {2.0f, 1.0f}};
  EXPECT_EQ(weightedMedianSelect(even, 2.0f), 1.0f);  // the lower one reaches half first
}

}  // namespace
}  // namespace lfcam::edof
