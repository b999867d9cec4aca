// Pieces of depth's cost volume (src/edof/cost_volume.cpp) against plain references on random
// inputs: the lowest subset per pixel, its planes a stride apart; the star of views.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

#include "edof/depth_stages.hpp"

namespace lfcam::edof {
namespace {

TEST(LowestSubset, IsEachPixelsMinimumOverThePlanesAndZeroWhereAllAreInfinite) {
  std::mt19937 generator(51);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  const float infinity = std::numeric_limits<float>::infinity();
  for (int trial = 0; trial < 20; ++trial) {
    // Pixel counts across the parallel grain (4096) and not a multiple of any vector width.
    const std::size_t n = 1 + generator() % 9000, subsets = 1 + generator() % 6, stride = n + generator() % 7;
    std::vector<float> planes(subsets * stride), out(n, 42.0f);
    for (float& value : planes) value = generator() % 10 == 0 ? infinity : uniform(generator);
    for (std::size_t p = 0; p < n; p += 97)  // some pixels with no finite cost at all
      for (std::size_t i = 0; i < subsets; ++i) planes[i * stride + p] = infinity;
    lowestSubset(planes.data(), subsets, stride, n, out.data());
    for (std::size_t p = 0; p < n; ++p) {
      float lowest = infinity;
      for (std::size_t i = 0; i < subsets; ++i) lowest = std::min(lowest, planes[i * stride + p]);
      ASSERT_EQ(out[p], lowest == infinity ? 0.0f : lowest) << "trial " << trial << " pixel " << p;
    }
  }
}

TEST(StarViews, TakesTheRowColumnAndDiagonalsAndEveryKthRingWhenAsked) {
  LightFieldShape shape;
  shape.nu = shape.nv = 9, shape.ns = shape.nt = 4, shape.channels = 1;
  const LightField lightField(shape);
  const std::vector<StarView> all = starViews(lightField, 4, 4, {});
  EXPECT_EQ(all.size(), 32u);
  const std::vector<StarView> even = starViews(lightField, 4, 4, {false, 2});
  ASSERT_EQ(even.size(), 16u);
  for (const StarView& view : even) {
    const int du = view.u - 4, dv = view.v - 4;
    EXPECT_EQ(std::max(std::abs(du), std::abs(dv)) % 2, 0) << view.u << ", " << view.v;
    EXPECT_TRUE(du == 0 || dv == 0 || std::abs(du) == std::abs(dv)) << view.u << ", " << view.v;
    EXPECT_EQ(view.uc, du);
    EXPECT_EQ(view.vc, dv);
  }
}

}  // namespace
}  // namespace lfcam::edof
