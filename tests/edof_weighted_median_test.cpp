// The weighted median by selection (src/edof/weighted_median.cpp) against the sorting reference,
// on random windows with ties, zero weights and the sizes the depth map's median uses; the depth
// map's guided median, flat and slanted.
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <tuple>
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
    std::vector<float> values(n + kMedianPadding), weights(n + kMedianPadding);
    for (int i = 0; i < n; ++i) {
      // A quarter of the values from a few levels (ties), some weights zero (the guide's table
      // underflows for very unlike neighbours).
      values[i] = coin(random) == 0 ? float(coin(random)) : value(random);
      weights[i] = coin(random) == 0 ? 0.0f : weight(random);
    }
    weights[0] = 1.0f;  // the centre pixel always counts fully
    float total = 0;
    for (int i = 0; i < n; ++i) total += weights[i];
    const float expected = weightedMedianSorted(values.data(), weights.data(), n, total);
    ASSERT_EQ(weightedMedianSelect(values.data(), weights.data(), n, total), expected)
        << "trial " << trial << ", " << n << " values";
  }
}

TEST(WeightedMedian, HeavyWeightWins) {
  std::vector<float> values = {5.0f, 1.0f, 3.0f, 2.0f}, weights = {0.1f, 0.1f, 10.0f, 0.1f};
  values.resize(4 + kMedianPadding), weights.resize(4 + kMedianPadding);
  EXPECT_EQ(weightedMedianSelect(values.data(), weights.data(), 4, 10.3f), 3.0f);
  std::vector<float> even = {1.0f, 2.0f}, equalWeights = {1.0f, 1.0f};
  even.resize(2 + kMedianPadding), equalWeights.resize(2 + kMedianPadding);
  EXPECT_EQ(weightedMedianSelect(even.data(), equalWeights.data(), 2, 2.0f), 1.0f);  // the lower one reaches half first
}

// The guided median's row kernel on every SIMD target against its one-neighbour-at-a-time
// reference, bit for bit, on random guides (some NaN) and maps (a ramp, so that the slopes are not
// all 0, with and without noise), window widths across the vectors' and images narrower than the
// window.
TEST(GuidedWeightedMedian, RowKernelAgreesWithTheReferenceOnEveryTarget) {
  std::mt19937 random(25);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), noise(-0.3f, 0.3f);
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  std::size_t pixels = 0, differing = 0;
  for (std::int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    for (const auto& [width, height, channels, radius] : std::vector<std::tuple<int, int, int, int>>{{37, 29, 3, 5},
                                                                                                     {70, 23, 3, 2},
                                                                                                     {9, 40, 1, 5},
                                                                                                     {6, 5, 3, 7},
                                                                                                     {33, 17, 3, 0},
                                                                                                     {1, 1, 3, 5},
                                                                                                     {64, 64, 3, 5}}) {
      Image guide(width, height, channels);
      for (float& sample : guide.pixels()) sample = unit(random) < 0.01f ? NAN : unit(random) * 0.3f;
      std::vector<float> map(std::size_t(width) * height);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
          map[std::size_t(y) * width + x] = 0.04f * x - 0.02f * y + (height % 2 ? noise(random) : 0.0f);
      for (bool slanted : {false, true}) {
        std::vector<float> fast = map, reference = map;
        guidedWeightedMedian(guide, radius, 0.05f, slanted, fast.data());
        guidedWeightedMedianReference(guide, radius, 0.05f, slanted, reference.data());
        for (std::size_t p = 0; p < map.size(); ++p) {
          if (fast[p] != reference[p] && !(std::isnan(fast[p]) && std::isnan(reference[p]))) ++differing;
          ++pixels;
        }
      }
    }
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the CPU's best
  EXPECT_EQ(differing, 0u) << "of " << pixels << " pixels";
}

// A guide of two colours split at column `edge`, the same in every channel.
Image twoColours(int size, int edge) {
  Image guide(size, size, 3);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) guide.at(x, y, c) = x < edge ? 0.2f : 0.8f;
  return guide;
}

// A surface slanted by 0.05 px per pixel with a colour edge on it (a painted line, a shadow): at the
// edge, a pixel's like-coloured neighbours all lie on one side. The flat median takes their
// disparity, more than 0.07 off; the slanted one carries each along the slope and keeps the ramp.
TEST(GuidedWeightedMedian, SlantedKeepsARampAtAColourEdge) {
  const int size = 40, edge = 20, radius = 5;
  const Image guide = twoColours(size, edge);
  std::vector<float> ramp(std::size_t(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) ramp[std::size_t(y) * size + x] = 0.05f * float(x);
  std::vector<float> flat = ramp, slanted = ramp;
  guidedWeightedMedian(guide, radius, 0.05f, false, flat.data());
  guidedWeightedMedian(guide, radius, 0.05f, true, slanted.data());
  const std::size_t atEdge = std::size_t(edge) * size + edge;
  EXPECT_GT(std::abs(flat[atEdge] - ramp[atEdge]), 0.07f);
  float worst = 0;
  for (int y = 5; y < size - 5; ++y)
    for (int x = 5; x < size - 5; ++x) {
      const std::size_t p = std::size_t(y) * size + x;
      worst = std::max(worst, std::abs(slanted[p] - ramp[p]));
    }
  EXPECT_LT(worst, 1e-4f);
}

// A surface slanted by 0.05 px per pixel that ends at a jump to a flat background of another
// colour (the far end of a floor, the side of a column): beside the jump a pixel's like-coloured
// neighbours all lie inwards. The flat median takes their disparity; the slanted one carries them
// along the slope measured a few pixels away on the same surface and keeps the ramp to its end.
TEST(GuidedWeightedMedian, SlantedKeepsARampUpToAJump) {
  const int size = 40, edge = 20, radius = 5;
  const Image guide = twoColours(size, edge);
  std::vector<float> map(std::size_t(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) map[std::size_t(y) * size + x] = x < edge ? 0.0f : 1.0f + 0.05f * float(x - edge);
  std::vector<float> flat = map, slanted = map;
  guidedWeightedMedian(guide, radius, 0.05f, false, flat.data());
  guidedWeightedMedian(guide, radius, 0.05f, true, slanted.data());
  const std::size_t besideJump = std::size_t(size / 2) * size + edge;
  EXPECT_GT(std::abs(flat[besideJump] - map[besideJump]), 0.07f);
  float worst = 0;  // up to the jump, away from the image's border
  for (int y = radius; y < size - radius; ++y)
    for (int x = edge; x < size - radius; ++x) {
      const std::size_t p = std::size_t(y) * size + x;
      worst = std::max(worst, std::abs(slanted[p] - map[p]));
    }
  EXPECT_LT(worst, 1e-4f);
}

// Beside a jump between two surfaces facing the camera, the slopes measured on either side are
// the map's noise, under the minimum: the slanted median does what the flat one does.
TEST(GuidedWeightedMedian, SlantedIsFlatBesideAJump) {
  const int size = 32;
  const Image guide = twoColours(size, size / 2);
  std::vector<float> step(std::size_t(size) * size);
  std::mt19937 random(3);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) step[std::size_t(y) * size + x] = (x < size / 2 ? 0.0f : 1.0f) + noise(random);
  std::vector<float> flat = step, slanted = step;
  guidedWeightedMedian(guide, 5, 0.05f, false, flat.data());
  guidedWeightedMedian(guide, 5, 0.05f, true, slanted.data());
  for (int y = 0; y < size; ++y)
    for (int x = size / 2 - 3; x < size / 2 + 3; ++x)
      EXPECT_EQ(slanted[std::size_t(y) * size + x], flat[std::size_t(y) * size + x]) << x << ", " << y;
}

}  // namespace
}  // namespace lfcam::edof
