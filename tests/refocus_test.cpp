// refocus (fast, float32) against refocusReference (float64 oracle), a focal stack against one
// refocus per slope, and properties that hold for any light field: slope 0 is the mean of the
// views, a flat field stays flat, an integer slope is an exact shift.
#include "lfcam/render/refocus.hpp"
#include "render/references.hpp"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "random_light_field.hpp"

namespace lfcam {
namespace {

using test::randomLightField;
using test::worstRelativeError;

TEST(Refocus, FastMatchesReferenceOnRandomLightFields) {
  std::mt19937 random(20050401);
  std::uniform_int_distribution<int> views(1, 6), pixels(1, 37);
  int cases = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const LightFieldShape shape{.nu = views(random),
                                .nv = views(random),
                                .ns = pixels(random),
                                .nt = pixels(random),
                                .channels = trial % 2 ? 3 : 1};
    const bool weighted = trial % 4 >= 2;
    const LightField lightField = randomLightField(shape, random, weighted);
    std::uniform_real_distribution<double> anySlope(-4.0, 4.0);
    // Fractional, negative, integer, and so large that the outer views leave the image.
    const double big = double(std::max(shape.ns, shape.nt)) + 3.5;
    for (double slope : {0.0, anySlope(random), anySlope(random), -1.0, 2.0, 0.5, 1e-9, big, -big / 2, 1e6}) {
      const Image fast = refocus(lightField, slope);
      const Image reference = refocusReference(lightField, slope);
      ASSERT_EQ(fast.width(), shape.ns);
      ASSERT_EQ(fast.height(), shape.nt);
      ASSERT_EQ(fast.channels(), shape.channels);
      EXPECT_LT(worstRelativeError(fast, reference), 1e-5)
          << "views " << shape.nu << "x" << shape.nv << ", pixels " << shape.ns << "x" << shape.nt << ", channels "
          << shape.channels << (weighted ? ", weighted" : "") << ", slope " << slope;
      ++cases;
    }
  }
  EXPECT_EQ(cases, 400);
}

TEST(Refocus, FastMatchesReferenceOnALargerWeightedField) {
  // Big enough for several row blocks and threads.
  std::mt19937 random(7);
  const LightField lightField = randomLightField({.nu = 5, .nv = 4, .ns = 203, .nt = 150, .channels = 3}, random, true);
  for (double slope : {-2.3, 0.75, 3.0})
    EXPECT_LT(worstRelativeError(refocus(lightField, slope), refocusReference(lightField, slope)), 1e-5)
        << "slope " << slope;
}

// The SIMD row kernels on every instruction set this CPU runs (Highway's dispatch forced to each
// in turn), at widths around the vector lengths (4, 8, 16 lanes) so that every tail and edge
// column path runs: odd widths, widths below one vector, one pixel wide; with rows of 1 to 11
// views, so that every number of rows summed in one pass (up to 9) and a split into two passes run.
TEST(Refocus, AFocalStackIsEachSlopesRefocus) {
  // Several row blocks and threads; slopes alike (sharing cached rows), far apart, 0 (one group of
  // views), and not a number (black), on a field with and without a weight plane.
  std::mt19937 random(11);
  const std::vector<double> slopes{-2.3, -2.25, 0.0, 0.75, NAN, 3.0, 0.8};
  for (bool weighted : {false, true}) {
    const LightField lightField =
        randomLightField({.nu = 5, .nv = 4, .ns = 171, .nt = 140, .channels = 3}, random, weighted);
    const std::vector<Image> stack = refocus(lightField, slopes);
    ASSERT_EQ(stack.size(), slopes.size());
    for (std::size_t k = 0; k < slopes.size(); ++k) {
      const Image one = refocus(lightField, slopes[k]);
      ASSERT_EQ(stack[k].pixels().size(), one.pixels().size());
      EXPECT_TRUE(std::equal(one.pixels().begin(), one.pixels().end(), stack[k].pixels().begin()))
          << "slope " << slopes[k] << (weighted ? ", weighted" : "");
      if (std::isfinite(slopes[k])) {
        EXPECT_LT(worstRelativeError(stack[k], refocusReference(lightField, slopes[k])), 1e-5) << "slope " << slopes[k];
      }
    }
  }
  EXPECT_TRUE(refocus(LightField(), std::vector<double>{1.0, 2.0}).front().empty());
}

TEST(Refocus, EverySimdTargetMatchesReferenceAtOddWidthsAndTails) {
  std::mt19937 random(1729);
  std::uniform_real_distribution<double> anySlope(-3.0, 3.0);
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (std::int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    for (int ns : {1, 2, 3, 5, 7, 9, 15, 17, 23, 31, 33, 47}) {
      for (bool weighted : {false, true}) {
        const int nu = 1 + (ns + (weighted ? 5 : 0)) % 11;
        const LightField lightField =
            randomLightField({.nu = nu, .nv = 2, .ns = ns, .nt = 5 + ns % 7, .channels = 3}, random, weighted);
        for (double slope : {0.0, 0.5, -1.0, anySlope(random), double(ns) + 0.25}) {
          EXPECT_LT(worstRelativeError(refocus(lightField, slope), refocusReference(lightField, slope)), 1e-5)
              << hwy::TargetName(target) << ", " << nu << " views across, width " << ns
              << (weighted ? ", weighted" : "") << ", slope " << slope;
        }
      }
    }
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the CPU's best
}

TEST(Refocus, SlopeZeroIsTheMeanOfTheViews) {
  std::mt19937 random(3);
  const LightField lightField = randomLightField({.nu = 4, .nv = 3, .ns = 64, .nt = 48, .channels = 3}, random, false);
  const Image photo = refocus(lightField, 0.0);
  for (int c = 0; c < 3; ++c)
    for (int t = 0; t < 48; ++t)
      for (int s = 0; s < 64; ++s) {
        double mean = 0;
        for (int v = 0; v < 3; ++v)
          for (int u = 0; u < 4; ++u) mean += lightField.at(u, v, s, t, c);
        mean /= 12;
        ASSERT_NEAR(photo.at(s, t, c), mean, 1e-6) << s << "," << t << "," << c;
      }
}

TEST(Refocus, FlatLightFieldStaysFlatAtAnySlope) {
  // Every pixel is reached by the centre view (odd view counts), so none may darken at the
  // borders, with or without a weight.
  for (bool weighted : {false, true}) {
    LightField lightField({.nu = 7, .nv = 5, .ns = 40, .nt = 31, .channels = 2});
    std::fill(lightField.samples().begin(), lightField.samples().end(), 0.37f);
    if (weighted) {
      std::mt19937 random(11);
      std::uniform_real_distribution<float> weight(0.1f, 1.0f);
      lightField.enableWeight();
      for (float& w : lightField.weights()) w = weight(random);
    }
    for (double slope : {-7.5, -1.3, 0.0, 0.25, 1.0, 2.6, 9.0}) {
      const Image photo = refocus(lightField, slope);
      float lowest = 1, highest = 0;
      for (float p : photo.pixels()) lowest = std::min(lowest, p), highest = std::max(highest, p);
      EXPECT_NEAR(lowest, 0.37f, 1e-6) << "slope " << slope << (weighted ? ", weighted" : "");
      EXPECT_NEAR(highest, 0.37f, 1e-6) << "slope " << slope << (weighted ? ", weighted" : "");
    }
  }
}

// An image I on the integer grid, and views of a surface of disparity k: view (u, v) at (s, t)
// sees I(s + u k, t + v k) (light_field.hpp), outside I's support a different constant.
TEST(Refocus, IntegerSlopeIsAnExactShift) {
  for (int views : {3, 4}) {
    const int k = 2, ns = 23, nt = 17;
    std::mt19937 random(views);
    // 8-bit values: sums of up to 16 of them are exact in float32, so equality can be exact.
    std::uniform_int_distribution<int> level(1, 255);
    const int margin = 8;
    std::vector<float> image(std::size_t(ns + 2 * margin) * (nt + 2 * margin));
    for (float& p : image) p = level(random) / 256.0f;
    auto I = [&](double x, double y) {
      return image[std::size_t(y + margin) * (ns + 2 * margin) + std::size_t(x + margin)];
    };
    LightField lightField({.nu = views, .nv = views, .ns = ns, .nt = nt, .channels = 1});
    for (int v = 0; v < views; ++v)
      for (int u = 0; u < views; ++u)
        for (int t = 0; t < nt; ++t)
          for (int s = 0; s < ns; ++s)
            lightField.at(u, v, s, t, 0) = I(s + lightField.uFromCentre(u) * k, t + lightField.vFromCentre(v) * k);
    // Even view counts put views at half steps: an even slope still shifts by whole pixels.
    const Image fast = refocus(lightField, k);
    const Image reference = refocusReference(lightField, k);
    for (int t = 0; t < nt; ++t)
      for (int s = 0; s < ns; ++s) {
        ASSERT_EQ(fast.at(s, t, 0), I(s, t)) << "views " << views << " at " << s << "," << t;
        ASSERT_EQ(reference.at(s, t, 0), I(s, t)) << "views " << views << " at " << s << "," << t;
      }
  }
}

TEST(Refocus, SamplesWithZeroWeightAreIgnored) {
  std::mt19937 random(5);
  LightField lightField = randomLightField({.nu = 3, .nv = 3, .ns = 30, .nt = 20, .channels = 1}, random, false);
  const Image unweighted = refocus(lightField, 1.5);
  // Weight 1 everywhere is the same as no weight.
  lightField.enableWeight(1.0f);
  const Image ones = refocus(lightField, 1.5);
  for (std::size_t i = 0; i < ones.pixels().size(); ++i) EXPECT_NEAR(ones.pixels()[i], unweighted.pixels()[i], 1e-6);
  // Samples that carry no light (weight 0) must not show, however bright they are.
  std::fill_n(lightField.plane(0, 2, 0), 600, 100.0f);
  std::fill_n(lightField.weightPlane(0, 2), 600, 0.0f);
  const Image masked = refocus(lightField, 1.5);
  for (float p : masked.pixels()) {
    EXPECT_GT(p, 0.0f);
    EXPECT_LT(p, 1.0f);
  }
}

TEST(Refocus, PixelsNoRayReachesAreZeroAndBadSlopesGiveBlack) {
  // Two views at u = -0.5 and +0.5 with slope 40 on a 10-pixel row: each is shifted by 20
  // pixels, out of the image entirely.
  LightField lightField({.nu = 2, .nv = 1, .ns = 10, .nt = 3, .channels = 1});
  std::fill(lightField.samples().begin(), lightField.samples().end(), 0.5f);
  // (Each photo is named: a loop over a temporary's pixels() would read freed memory.)
  const Image fast = refocus(lightField, 40.0), reference = refocusReference(lightField, 40.0);
  const Image notANumber = refocus(lightField, NAN);
  for (const Image* photo : {&fast, &reference, &notANumber})
    for (float p : photo->pixels()) EXPECT_EQ(p, 0.0f);
  EXPECT_TRUE(refocus(LightField(), 1.0).empty());
}

}  // namespace
}  // namespace lfcam
