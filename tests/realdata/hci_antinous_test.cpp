// Refocusing the real HCI benchmark scene "antinous" (9x9 views of 512x512) against its
// ground-truth disparity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/render/focal_stack.hpp"
#include "lfcam/render/refocus.hpp"
#include "sharpness.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

class HciAntinous : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto dir = test::sharedDataDir() / "hci-antinous";
    if (!std::filesystem::exists(dir)) return;
    auto lf = readLightField(dir);
    ASSERT_TRUE(lf) << lf.error().message;
    lightField_ = new LightField(std::move(*lf));
    auto gt = readImage(dir / "gt_disp_lowres.pfm");
    ASSERT_TRUE(gt) << gt.error().message;
    groundTruth_ = new Image(std::move(*gt));
  }
  static void TearDownTestSuite() {
    delete lightField_;
    delete groundTruth_;
    lightField_ = nullptr;
    groundTruth_ = nullptr;
  }
  void SetUp() override {
    LFCAM_REQUIRE_SHARED_DATA("hci-antinous", dir);
    ASSERT_NE(lightField_, nullptr);
  }
  static LightField* lightField_;
  static Image* groundTruth_;
};
LightField* HciAntinous::lightField_ = nullptr;
Image* HciAntinous::groundTruth_ = nullptr;

TEST_F(HciAntinous, LoadsAsNineByNineViewsWithItsDisparityRange) {
  const LightField& lf = *lightField_;
  EXPECT_EQ(lf.shape(), (LightFieldShape{.nu = 9, .nv = 9, .ns = 512, .nt = 512, .channels = 3}));
  ASSERT_TRUE(lf.metadata.disparityMin && lf.metadata.disparityMax);
  EXPECT_DOUBLE_EQ(*lf.metadata.disparityMin, -3.3);
  EXPECT_DOUBLE_EQ(*lf.metadata.disparityMax, 2.8);
  EXPECT_EQ(groundTruth_->width(), 512);
  EXPECT_EQ(groundTruth_->channels(), 1);
}

TEST_F(HciAntinous, SlopeZeroIsTheMeanOfTheViews) {
  const LightField& lf = *lightField_;
  const Image photo = refocus(lf, 0.0);
  double worst = 0;
  for (int c = 0; c < lf.channels(); ++c)
    for (std::size_t i = 0; i < lf.shape().viewPixels(); i += 97) {
      double mean = 0;
      for (int v = 0; v < lf.nv(); ++v)
        for (int u = 0; u < lf.nu(); ++u) mean += lf.plane(u, v, c)[i];
      mean /= double(lf.shape().views());
      worst = std::max(worst, std::abs(mean - photo.plane(c)[i]));
    }
  EXPECT_LT(worst, 1e-5);
}

// In windows where the ground truth is nearly constant, refocusing at that disparity must beat
// refocusing at either end of the scene's disparity range.
TEST_F(HciAntinous, RegionIsSharpestAtItsGroundTruthDisparity) {
  const LightField& lf = *lightField_;
  const Image& gt = *groundTruth_;
  constexpr int window = 48;
  struct Region {
    int x, y;
    double disparity;
  };
  std::vector<Region> regions;
  for (int y = 16; y + window <= 512 - 16; y += window / 2)
    for (int x = 16; x + window <= 512 - 16; x += window / 2) {
      double lo = 1e9, hi = -1e9, sum = 0;
      for (int j = y; j < y + window; ++j)
        for (int i = x; i < x + window; ++i) {
          const double d = gt.at(i, j, 0);
          lo = std::min(lo, d), hi = std::max(hi, d), sum += d;
        }
      if (hi - lo < 0.3) regions.push_back({x, y, sum / (window * window)});
    }
  ASSERT_GE(regions.size(), 2u);
  // The nearest and the farthest flat region: the hardest pair for a single focus.
  auto [nearest, farthest] = std::minmax_element(
      regions.begin(), regions.end(), [](const Region& a, const Region& b) { return a.disparity > b.disparity; });
  const double ends[2] = {*lf.metadata.disparityMin, *lf.metadata.disparityMax};
  const Image atEnds[2] = {refocus(lf, ends[0]), refocus(lf, ends[1])};
  for (const Region* region : {&*nearest, &*farthest}) {
    const Image focused = refocus(lf, region->disparity);
    const auto sharpness = [&](const Image& image) {
      return test::laplacianVariance(image, region->x, region->y, region->x + window, region->y + window);
    };
    const double atTruth = sharpness(focused);
    SCOPED_TRACE("region at (" + std::to_string(region->x) + ", " + std::to_string(region->y) + "), disparity " +
                 std::to_string(region->disparity));
    EXPECT_GT(atTruth, 1.5 * sharpness(atEnds[0]));
    EXPECT_GT(atTruth, 1.5 * sharpness(atEnds[1]));
  }
}

// Click-to-focus (--focus-at): at the most textured points of the centre view where the ground
// truth is flat (so that the answer is one number), the slope found is the true disparity.
TEST_F(HciAntinous, FocusAtAPixelFindsItsGroundTruthDisparity) {
  const LightField& lf = *lightField_;
  const Image& gt = *groundTruth_;
  const Image centre = lf.subApertureImage(4, 4);
  struct Point {
    int x, y;
    double texture;
  };
  std::vector<Point> points;
  for (int y = 24; y < 512 - 24; y += 16)
    for (int x = 24; x < 512 - 24; x += 16) {
      double lo = 1e9, hi = -1e9;
      for (int j = y - 4; j <= y + 4; ++j)
        for (int i = x - 4; i <= x + 4; ++i)
          lo = std::min(lo, double(gt.at(i, j, 0))), hi = std::max(hi, double(gt.at(i, j, 0)));
      if (hi - lo < 0.05) points.push_back({x, y, test::laplacianVariance(centre, x - 4, y - 4, x + 5, y + 5)});
    }
  ASSERT_GE(points.size(), 6u);
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.texture > b.texture; });
  points.resize(6);
  for (const Point& point : points) {
    auto slope = slopeAtPixel(lf, point.x, point.y);
    ASSERT_TRUE(slope) << slope.error().message;
    const double truth = gt.at(point.x, point.y, 0);
    std::printf("focus at (%d, %d): slope %.3f, ground truth %.3f\n", point.x, point.y, *slope, truth);
    EXPECT_NEAR(*slope, truth, 0.1) << "at (" << point.x << ", " << point.y << ")";
  }
}

}  // namespace
}  // namespace lfcam
