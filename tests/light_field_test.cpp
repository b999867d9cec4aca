#include "lfcam/core/light_field.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace lfcam {
namespace {

TEST(LightField, LayoutIsViewsOutermostThenChannelThenRows) {
  LightField lf({.nu = 3, .nv = 2, .ns = 5, .nt = 4, .channels = 2});
  lf.at(2, 1, 4, 3, 1) = 7.0f;
  const std::size_t index = (((1 * 3 + 2) * 2 + 1) * 4 + 3) * 5 + 4;
  EXPECT_EQ(lf.samples()[index], 7.0f);
  EXPECT_EQ(lf.samples().size(), std::size_t(3 * 2 * 5 * 4 * 2));
}

TEST(LightField, CentreIsHalfIntegerForEvenViewCounts) {
  LightField odd({.nu = 9, .nv = 9, .ns = 1, .nt = 1, .channels = 1});
  EXPECT_EQ(odd.uFromCentre(4), 0.0);
  EXPECT_EQ(odd.vFromCentre(0), -4.0);
  LightField even({.nu = 10, .nv = 10, .ns = 1, .nt = 1, .channels = 1});
  EXPECT_EQ(even.uFromCentre(4), -0.5);
  EXPECT_EQ(even.uFromCentre(5), 0.5);
}

TEST(LightField, SubApertureImageRoundTripsAndCopyIsDeep) {
  LightField lf({.nu = 2, .nv = 2, .ns = 3, .nt = 2, .channels = 3});
  Image view(3, 2, 3);
  for (std::size_t i = 0; i < view.pixels().size(); ++i) view.pixels()[i] = float(i);
  lf.setSubApertureImage(1, 0, view);
  Image back = lf.subApertureImage(1, 0);
  for (std::size_t i = 0; i < view.pixels().size(); ++i) EXPECT_EQ(back.pixels()[i], view.pixels()[i]);
  LightField other = lf.copy();
  other.at(1, 0, 0, 0, 0) = -1.0f;
  EXPECT_EQ(lf.at(1, 0, 0, 0, 0), 0.0f);
}

TEST(LightField, WeightHasOnePlanePerView) {
  LightField lf({.nu = 2, .nv = 3, .ns = 4, .nt = 5, .channels = 3});
  EXPECT_FALSE(lf.hasWeight());
  lf.enableWeight(0.5f);
  ASSERT_TRUE(lf.hasWeight());
  EXPECT_EQ(lf.weights().size(), std::size_t(2 * 3 * 4 * 5));
  lf.weightPlane(1, 2)[19] = 0.25f;
  EXPECT_EQ(lf.weights().back(), 0.25f);
}

// The allocator hands out zeroed memory and the constructor does not fill it again: check both
// sizes of buffer (operator new below 4 MiB, aligned huge pages above), reused memory included.
TEST(LightField, NewSamplesAndZeroWeightsAreZero) {
  for (Pages pages : {Pages::Huge, Pages::Ordinary}) {
    // 2 KB of samples (operator new) and 5.1 MB (above the 4 MiB of the aligned path)
    for (int side : {8, 400}) {
      for (int round = 0; round < 2; ++round) {
        LightField lf({.nu = 2, .nv = 2, .ns = side, .nt = side, .channels = 2}, pages);
        std::size_t nonZero = 0;
        for (float x : lf.samples()) nonZero += x != 0.0f;
        lf.enableWeight(0.75f);
        lf.enableWeight(0.0f);
        for (float w : lf.weights()) nonZero += w != 0.0f;
        EXPECT_EQ(nonZero, 0u) << side;
        std::fill(lf.samples().begin(), lf.samples().end(), 3.0f);  // leaves garbage for round 2's buffer
      }
    }
  }
}

TEST(Optics, AlphaAndSlopeAreInverse) {
  Optics optics{.lensStepMm = 2.5, .spatialStepMm = 0.125, .lensToMicrolensMm = 100};
  EXPECT_DOUBLE_EQ(optics.slopeFromAlpha(1.0), 0.0);
  for (double alpha : {0.8, 0.95, 1.05, 1.3})
    EXPECT_NEAR(optics.alphaFromSlope(optics.slopeFromAlpha(alpha)), alpha, 1e-12);
  // Film moved back (alpha > 1) focuses nearer: positive slope in the HCI convention.
  EXPECT_GT(optics.slopeFromAlpha(1.1), 0.0);
}

}  // namespace
}  // namespace lfcam
