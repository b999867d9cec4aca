// Keys's cubic sampler (core/cubic.hpp) on random planes: the samples themselves at whole
// positions, constants reproduced (and planes a + b x + c y by Catmull-Rom) inside, and the border
// extended outwards.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/cubic.hpp"

namespace lfcam {
namespace {

TEST(CubicSample, InterpolatesReproducesPlanesAndExtendsTheBorder) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0, 1);
  const int width = 9, height = 7;
  std::vector<float> noise(std::size_t(width) * height), ramp(noise.size()), flat(noise.size(), 0.25f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      noise[std::size_t(y) * width + x] = float(unit(random));
      ramp[std::size_t(y) * width + x] = float(0.5 + 0.25 * x - 0.125 * y);
    }
  for (const double a : {kCatmullRom, -0.75}) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        EXPECT_FLOAT_EQ(cubicSample(noise.data(), width, height, x, y, a), noise[std::size_t(y) * width + x]);
    for (int k = 0; k < 100; ++k) {
      const double x = 1 + unit(random) * (width - 4), y = 1 + unit(random) * (height - 4);
      if (a == kCatmullRom)
        EXPECT_NEAR(cubicSample(ramp.data(), width, height, x, y, a), 0.5 + 0.25 * x - 0.125 * y, 1e-5);
      EXPECT_NEAR(cubicSample(flat.data(), width, height, x, y, a), 0.25, 1e-6);
      // Beyond the plane: its nearest border pixel's row or column.
      EXPECT_FLOAT_EQ(cubicSample(noise.data(), width, height, -3 - 1e9 * unit(random), 0, a), noise[0]);
      EXPECT_FLOAT_EQ(cubicSample(noise.data(), width, height, width + 2 + 1e9 * unit(random), height + 1e9, a),
                      noise.back());
    }
  }
}

}  // namespace
}  // namespace lfcam
