// The all-in-focus photomontage (all_in_focus.hpp) on a noisy layered-planes light field: the
// point of the paper's Figure 15. In every plane's region the composite is as sharp as the
// best-focused photograph of the focal stack (within 5%), and at least 3x less noisy than the
// central sub-aperture image, which has the same depth of field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "sharpness.hpp"

namespace lfcam {
namespace {

struct Region {
  const char* name;
  double disparity;
  int x0, y0, x1, y1;  // inside one plane, clear of occlusion boundaries
};

// The default scene at 128x128 (layered_planes.cpp lays it out for 256: half these numbers).
const Region kRegions[] = {
    {"background", -1.0, 85, 4, 123, 30},
    {"checkerboard", 0.0, 20, 22, 50, 45},
    {"striped ellipse", 0.8, 82, 62, 100, 82},
    {"ringed card", 1.6, 36, 86, 70, 112},
};

double rmsDifference(const Image& a, const Image& b, const Region& r) {
  double sum = 0;
  long count = 0;
  for (int c = 0; c < a.channels(); ++c)
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const double d = a.at(x, y, c) - b.at(x, y, c);
        sum += d * d, ++count;
      }
  return std::sqrt(sum / count);
}

class AllInFocusNoisy : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    clean_ = new LayeredPlanesLightField(renderLayeredPlanes(defaultLayeredPlanesScene(9, 128)));
    noisy_ = new LightField(clean_->lightField.copy());
    noisy_->metadata = clean_->lightField.metadata;
    // Read noise plus photon noise, per sample: sigma^2 = 0.02^2 + 0.002 x value.
    std::mt19937 generator(7);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    for (float& sample : noisy_->samples())
      sample += std::sqrt(0.0004f + 0.002f * std::max(sample, 0.0f)) * normal(generator);
  }
  static void TearDownTestSuite() {
    delete clean_;
    delete noisy_;
  }
  static LayeredPlanesLightField* clean_;
  static LightField* noisy_;
};
LayeredPlanesLightField* AllInFocusNoisy::clean_ = nullptr;
LightField* AllInFocusNoisy::noisy_ = nullptr;

void expectFigure15(const LightField& noisy, const LightField& clean, const AllInFocus& result) {
  const Image centreNoisy = noisy.subApertureImage(4, 4), centreClean = clean.subApertureImage(4, 4);
  for (const Region& region : kRegions) {
    SCOPED_TRACE(region.name);
    auto sharpness = [&](const Image& image) {
      return test::laplacianVariance(image, region.x0, region.y0, region.x1, region.y1);
    };
    double best = 0;
    for (double slope : result.slopes) best = std::max(best, sharpness(refocus(noisy, slope)));
    const double composite = sharpness(result.photo);
    // Noise: the difference from the noise-free photograph focused on the plane, against the
    // centre view's difference from its noise-free self.
    const double compositeNoise = rmsDifference(result.photo, refocus(clean, region.disparity), region);
    const double centreNoise = rmsDifference(centreNoisy, centreClean, region);
    std::printf("%-16s sharpness %.3g of best slice %.3g; noise %.4f vs centre view %.4f (%.1fx)\n", region.name,
                composite, best, compositeNoise, centreNoise, centreNoise / compositeNoise);
    EXPECT_GE(composite, 0.95 * best);
    EXPECT_GE(centreNoise, 3 * compositeNoise);
  }
}

TEST_F(AllInFocusNoisy, FocusMeasureCompositeIsSharpAndQuiet) {
  // Slices every 0.2 from -1 to 1.6: each plane lies on one.
  auto result = allInFocus(*noisy_, {.sliceStep = 0.2});
  ASSERT_TRUE(result) << result.error().message;
  ASSERT_EQ(result->slopes.size(), 14u);
  EXPECT_EQ(result->photo.channels(), 3);
  expectFigure15(*noisy_, clean_->lightField, *result);
}

TEST_F(AllInFocusNoisy, DepthMapCompositeIsSharpAndQuiet) {
  auto result = allInFocus(*noisy_, {.disparity = &clean_->disparity, .sliceStep = 0.2});
  ASSERT_TRUE(result) << result.error().message;
  // The slices follow the map: in each region, the plane's own slope.
  for (const Region& region : kRegions)
    EXPECT_NEAR(result->slope.at((region.x0 + region.x1) / 2, (region.y0 + region.y1) / 2, 0), region.disparity, 1e-6);
  expectFigure15(*noisy_, clean_->lightField, *result);
}

TEST(AllInFocus, FlatFieldStaysFlatAndBadInputIsRefused) {
  LightField flat({.nu = 5, .nv = 5, .ns = 40, .nt = 30, .channels = 2});
  for (float& s : flat.samples()) s = 0.25f;
  auto result = allInFocus(flat);
  ASSERT_TRUE(result) << result.error().message;
  for (float v : result->photo.pixels()) ASSERT_NEAR(v, 0.25f, 1e-5f);
  const Image wrongSize(10, 10, 1);
  EXPECT_FALSE(allInFocus(flat, {.disparity = &wrongSize}));
  EXPECT_FALSE(allInFocus(LightField()));
}

}  // namespace
}  // namespace lfcam
