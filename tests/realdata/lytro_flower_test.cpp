// A real first-generation Lytro capture, decoded by another toolbox into 10x10 views named
// IMG_0001_NNN_RR_CC.png (NNN a serpentine counter, RR row, CC column).
#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/light_field_io.hpp"
#include "lfcam/refocus.hpp"
#include "sharpness.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

// The views (u in [u0, u1), v in [v0, v1)) as a light field of their own.
LightField subset(const LightField& lf, int u0, int u1, int v0, int v1) {
  LightField part({.nu = u1 - u0, .nv = v1 - v0, .ns = lf.ns(), .nt = lf.nt(), .channels = lf.channels()});
  for (int v = v0; v < v1; ++v)
    for (int u = u0; u < u1; ++u) part.setSubApertureImage(u - u0, v - v0, lf.subApertureImage(u, v));
  return part;
}

// The slope in [-2, 2] (steps of 0.1) that makes the middle of the image sharpest, and how much
// sharper it is there than at the worst slope.
std::pair<double, double> sharpestSlope(const LightField& lf) {
  double best = 0, bestSharpness = -1, worstSharpness = 1e30;
  for (int i = -20; i <= 20; ++i) {
    const double slope = i * 0.1;
    const double sharpness = test::laplacianVariance(refocus(lf, slope), 64, 64, 192, 192);
    if (sharpness > bestSharpness) bestSharpness = sharpness, best = slope;
    worstSharpness = std::min(worstSharpness, sharpness);
  }
  return {best, bestSharpness / worstSharpness};
}

TEST(LytroFlower, LoadsInViewOrderAndRefocuses) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-f01-flower", dir);
  auto lf = readLightField(dir);
  ASSERT_TRUE(lf) << lf.error().message;
  EXPECT_EQ(lf->shape(), (LightFieldShape{.nu = 10, .nv = 10, .ns = 256, .nt = 256, .channels = 3}));

  // Refocusing works: one slope is clearly sharper than the worst.
  const auto [slope, gain] = sharpestSlope(*lf);
  EXPECT_GT(gain, 1.5) << "best slope " << slope;
  EXPECT_GT(std::abs(slope), 0.05) << "the flower is not at the captured focus";

  // Right view order: a row of views (u varies) and a column of views (v varies) bring the same
  // surface into focus at the same slope. Swapped or reversed axes, or views taken in the
  // serpentine capture order, would give another slope, or a wrong sign.
  const auto [rowSlope, rowGain] = sharpestSlope(subset(*lf, 1, 9, 4, 6));
  const auto [columnSlope, columnGain] = sharpestSlope(subset(*lf, 4, 6, 1, 9));
  EXPECT_NEAR(rowSlope, slope, 0.25);
  EXPECT_NEAR(columnSlope, slope, 0.25);
  EXPECT_GT(rowGain, 1.2);
  EXPECT_GT(columnGain, 1.2);
}

}  // namespace
}  // namespace lfcam
