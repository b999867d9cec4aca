// Refocusing the real HCI benchmark scene "antinous" (9x9 views of 512x512) against its
// ground-truth disparity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "lfcam/image_io.hpp"
#include "lfcam/light_field_io.hpp"
#include "lfcam/refocus.hpp"
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
  auto [nearest, farthest] = std::minmax_element(regions.begin(), regions.end(),
                                                 [](const Region& a, const Region& b) { return a.disparity > b.disparity; });
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

}  // namespace
}  // namespace lfcam
