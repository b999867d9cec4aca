// Virtual depth of a focused plenoptic capture, against the simulator's truth.
#include <gtest/gtest.h>

#include <cmath>

#include "focused_camera.hpp"
#include "lfcam/focused/focused_depth.hpp"

namespace lfcam {
namespace {

struct DepthScore {
  double badPix = 0;         // share of pixels whose disparity D / v is off by more than 0.25 px
  double relativeError = 0;  // mean |v - v_true| / v_true
};

DepthScore score(const Image& estimate, const Image& truth, double diameter, int margin) {
  DepthScore s;
  int count = 0;
  for (int y = margin; y < truth.height() - margin; ++y)
    for (int x = margin; x < truth.width() - margin; ++x) {
      const double v = estimate.at(x, y, 0), t = truth.at(x, y, 0);
      s.badPix += std::abs(diameter / v - diameter / t) > 0.25;
      s.relativeError += std::abs(v - t) / t;
      ++count;
    }
  s.badPix /= count;
  s.relativeError /= count;
  return s;
}

TEST(FocusedDepth, FindsTheLayersVirtualDepths) {
  const test::FocusedCapture& c = test::galileanCapture();
  FocusedDepthRequest request;
  request.pixelsPerLens = test::kFocusedPixelsPerLens;
  auto depth = estimateFocusedDepth(c.image, c.calibration, request);
  ASSERT_TRUE(depth) << depth.error().message;
  const DepthScore s =
      score(depth->virtualDepth, c.truth.virtualDepth, c.calibration.diameterPx(), int(test::kFocusedPixelsPerLens));
  std::printf("layers at v = 3.2, 4.6, 6: BadPix(0.25 px) %.2f %%, relative error in v %.2f %%\n", 100 * s.badPix,
              100 * s.relativeError);
  EXPECT_LT(s.badPix, 0.1);
}

}  // namespace
}  // namespace lfcam
