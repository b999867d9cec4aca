// A real first-generation Lytro capture, decoded by another toolbox into 10x10 views named
// IMG_0001_NNN_RR_CC.png (NNN a serpentine counter, RR row, CC column).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <utility>

#include "lfcam/io/light_field_io.hpp"
#include "lfcam/render/focal_stack.hpp"
#include "lfcam/render/refocus.hpp"
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

// The sign of the slope. The centre view (IMG_0001_045_05_05.png) shows two pink flowers in the
// middle, their yellow centres at about (110, 65) and (158, 118), standing in front of the ground
// cover around them. Measured with --focus-at, everything lies
// at negative slopes: the camera's optical focus plane is nearer than the whole scene (the
// first-generation Lytro focuses close and refocuses out to infinity), and a negative slope is
// farther than that plane (light_field.hpp; alpha < 1 in the paper). So the expected signs:
// the flowers come into focus at a negative slope, not at its mirror image, and, being nearer,
// at a larger slope than the far ground. Views read in the wrong order or mirrored would flip
// both.
TEST(LytroFlower, NearFlowerFocusesAtTheExpectedSignOfSlope) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-f01-flower", dir);
  auto lf = readLightField(dir);
  ASSERT_TRUE(lf) << lf.error().message;
  const FocusSearch search{.minSlope = -1.5, .maxSlope = 1.5, .steps = 151, .radius = 4};
  double flowerSlope = 1e9, groundSlope = -1e9;
  for (auto [x, y] : {std::pair{110, 65}, std::pair{158, 118}}) {
    auto slope = slopeAtPixel(*lf, x, y, search);
    ASSERT_TRUE(slope) << slope.error().message;
    flowerSlope = std::min(flowerSlope, *slope);  // the farther of the two flowers
  }
  for (auto [x, y] : {std::pair{30, 60}, std::pair{220, 40}}) {
    auto slope = slopeAtPixel(*lf, x, y, search);
    ASSERT_TRUE(slope) << slope.error().message;
    groundSlope = std::max(groundSlope, *slope);  // the nearer of the two ground points
  }
  EXPECT_LT(flowerSlope, -0.3);
  EXPECT_GT(flowerSlope, groundSlope + 0.02) << "the flowers must be nearer than the far ground";

  // Refocusing at that slope sharpens the flowers; its mirror image blurs them.
  const Image focused = refocus(*lf, flowerSlope), mirrored = refocus(*lf, -flowerSlope);
  for (auto [x0, y0, x1, y1] : {std::array{75, 35, 150, 95}, std::array{115, 85, 210, 150}}) {
    const double sharp = test::laplacianVariance(focused, x0, y0, x1, y1);
    const double blurred = test::laplacianVariance(mirrored, x0, y0, x1, y1);
    EXPECT_GT(sharp, 1.5 * blurred) << "flower window (" << x0 << ", " << y0 << ")";
  }
}

}  // namespace
}  // namespace lfcam
