// The HCI benchmark's scores (disparity_scores.hpp) on errors whose scores are known by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lfcam/edof/disparity_scores.hpp"

namespace lfcam {
namespace {

template <typename F>
Image imageOf(int width, int height, F value) {
  Image image(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y, 0) = float(value(x, y));
  return image;
}

// A slanted plane beside a step: two planes and the band of an edge between them.
double stepScene(int x, int y) { return 0.01 * x - 0.02 * y + (x >= 32 ? 1.0 : 0.0); }

TEST(DisparityScores, BadPixAndMseCountErrorsAboveEachThreshold) {
  const Image truth = imageOf(40, 40, [](int, int) { return 0.5; });
  // Errors 0.02 in the left half, 0.05 in the right: BadPix(0.01) all, (0.03) half, (0.07) none.
  const Image estimate = imageOf(40, 40, [](int x, int) { return x < 20 ? 0.52 : 0.55; });
  auto scores = scoreHci(estimate, truth, {}, 0);
  ASSERT_TRUE(scores) << scores.error().message;
  EXPECT_NEAR(scores->badPix001, 100.0, 1e-9);
  EXPECT_NEAR(scores->badPix003, 50.0, 1e-9);
  EXPECT_NEAR(scores->badPix007, 0.0, 1e-9);
  EXPECT_NEAR(scores->mse100, 100.0 * (0.02 * 0.02 + 0.05 * 0.05) / 2, 1e-6);
  EXPECT_EQ(scores->pixels, 1600);
}

TEST(DisparityScores, FartherShareCountsTheBadPixelsBelowTheTruth) {
  const Image truth = imageOf(40, 40, [](int, int) { return 0.5; });
  // Rows 0-9 farther by 0.1, rows 10-19 nearer by 0.1, the rest right: half of the bad are farther;
  // with the nearer rows only within the threshold, all of them.
  const Image estimate = imageOf(40, 40, [](int, int y) { return y < 10 ? 0.4 : y < 20 ? 0.6 : 0.5; });
  auto both = scoreDisparity(estimate, truth, 0.07, 0);
  ASSERT_TRUE(both) << both.error().message;
  EXPECT_NEAR(both->badPix, 50.0, 1e-9);
  EXPECT_NEAR(both->fartherShare, 50.0, 1e-9);
  const Image farOnly = imageOf(40, 40, [](int, int y) { return y < 10 ? 0.4 : y < 20 ? 0.55 : 0.5; });
  auto one = scoreDisparity(farOnly, truth, 0.07, 0);
  ASSERT_TRUE(one) << one.error().message;
  EXPECT_NEAR(one->fartherShare, 100.0, 1e-9);
  auto none = scoreDisparity(truth, truth, 0.07, 0);
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_EQ(none->fartherShare, 0.0);
}

TEST(DisparityScores, PlanarMaskKeepsPlanesAndLeavesOutTheBandOfAnEdge) {
  const Image mask = planarMask(imageOf(64, 48, stepScene));
  for (int x = 2; x < 62; ++x) {               // the repeated image border bends a slant in the outer two pixels
    const bool nearEdge = x >= 30 && x <= 33;  // two Scharr passes reach two pixels
    EXPECT_EQ(mask.at(x, 20, 0), nearEdge ? 0.0f : 1.0f) << x;
  }
  // A curved surface is not planar.
  const Image bowl = planarMask(imageOf(64, 48, [](int x, int y) { return 0.001 * (x * x + y * y); }));
  EXPECT_EQ(bowl.at(20, 20, 0), 0.0f);
}

TEST(DisparityScores, BumpinessIsZeroForAPlanarErrorAndFourTimesTheCurvatureOfACurvedOne) {
  const Image truth = imageOf(64, 48, stepScene);
  // An error that is itself a plane (a tilt, an offset) is not bumpy.
  const Image tilted = imageOf(64, 48, [](int x, int y) { return stepScene(x, y) + 0.3 + 0.004 * x + 0.002 * y; });
  auto flat = bumpiness(tilted, truth);
  ASSERT_TRUE(flat) << flat.error().message;
  EXPECT_NEAR(*flat, 0.0, 1e-4);  // float rounding of the images
  // Error k x^2 / 2: the Hessian is 4 k along x (twice-the-derivative Scharr, twice), clipped at 0.05.
  for (const double k : {0.002, 0.005, 0.05}) {
    const Image curved = imageOf(64, 48, [k](int x, int y) { return stepScene(x, y) + k * x * x / 2; });
    auto rough = bumpiness(curved, truth, {}, 2);
    ASSERT_TRUE(rough);
    EXPECT_NEAR(*rough, 100.0 * std::min(4 * k, 0.05), 1e-3) << k;
  }
}

TEST(DisparityScores, BumpinessUsesTheGivenMaskAndCountsHolesAsTheClip) {
  const Image truth = imageOf(64, 48, stepScene);
  Image estimate = imageOf(64, 48, stepScene);
  estimate.at(10, 10, 0) = std::numeric_limits<float>::quiet_NaN();
  // Only the hole's neighbourhood in the mask: every masked pixel there is a clip.
  const Image nearHole = imageOf(64, 48, [](int x, int y) { return std::abs(x - 10) <= 2 && std::abs(y - 10) <= 2; });
  auto holes = bumpiness(estimate, truth, nearHole, 0);
  ASSERT_TRUE(holes);
  EXPECT_NEAR(*holes, 5.0, 1e-9);
  // Far from the hole, nothing.
  const Image far = imageOf(64, 48, [](int x, int y) { return x > 40 && y > 30; });
  auto clean = bumpiness(estimate, truth, far, 0);
  ASSERT_TRUE(clean);
  EXPECT_NEAR(*clean, 0.0, 1e-6);
}

TEST(DisparityScores, RefusesImagesOfAnotherSizeAndMasksWithNoPlane) {
  EXPECT_FALSE(scoreHci(Image(8, 8, 1), Image(9, 8, 1)));
  EXPECT_FALSE(bumpiness(Image(8, 8, 1), Image(8, 8, 1), Image(8, 9, 1), 0));
  const Image bowl = imageOf(40, 40, [](int x, int y) { return 0.01 * (x * x + y * y); });
  EXPECT_FALSE(bumpiness(bowl, bowl, {}, 0)) << "no planar pixel";
}

}  // namespace
}  // namespace lfcam
