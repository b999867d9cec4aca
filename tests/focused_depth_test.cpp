// Virtual depth of a focused plenoptic capture, against the simulator's truth.
#include <gtest/gtest.h>

#include <cmath>

#include "focused_camera.hpp"
#include "lfcam/focused/focused_depth.hpp"

namespace lfcam {
namespace {

TEST(FocusedDepth, FindsTheLayersVirtualDepths) {
  const test::FocusedCapture& c = test::galileanCapture();
  FocusedDepthRequest request;
  request.pixelsPerLens = test::kFocusedPixelsPerLens;
  auto depth = estimateFocusedDepth(c.image, c.calibration, request);
  ASSERT_TRUE(depth) << depth.error().message;
  const test::VirtualDepthScore s = test::scoreVirtualDepth(
      depth->virtualDepth, c.truth.virtualDepth, c.calibration.diameterPx(), int(test::kFocusedPixelsPerLens));
  std::printf("layers at v = 3.2, 4.6, 6: BadPix(0.25 px) %.2f %%, relative error in v %.2f %%\n", 100 * s.badPix,
              100 * s.relativeError);
  EXPECT_LT(s.badPix, 0.1);
}

// The calibration's optics turn virtual depth back into the distance the simulator put it at (its
// forward formula, focusedVirtualDepth, is written apart from the library's inverse).
TEST(FocusedDepth, VirtualDepthTurnsIntoTheDistanceOfThePoint) {
  for (const bool galilean : {true, false}) {
    const CameraModel camera = test::focusedCamera({.galilean = galilean});
    const auto calibration = focusedCalibrationFromCamera(camera);
    ASSERT_TRUE(calibration && calibration->optics);
    for (const double z : {galilean ? 700.0 : 800.0, 1000.0, 1500.0}) {
      const double v = focusedVirtualDepth(camera, z);
      EXPECT_GT(v, 0) << z;
      EXPECT_NEAR(distanceOfVirtualDepth(*calibration->optics, calibration->orientation, v), z, 1e-9 * z)
          << (galilean ? "Galilean" : "Keplerian") << " at " << z << " mm (v " << v << ")";
    }
  }
}

}  // namespace
}  // namespace lfcam
