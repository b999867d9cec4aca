// Rendering a focused plenoptic capture, against the simulator's ideal photograph.
#include <gtest/gtest.h>

#include <cmath>

#include "focused_camera.hpp"
#include "lfcam/focused/focused_depth.hpp"
#include "lfcam/focused/focused_render.hpp"
#include "lfcam/focused/seam_energy.hpp"

namespace lfcam {
namespace {

TEST(FocusedRender, TotalFocusWithTheTrueDepthsMatchesTheIdealPhotograph) {
  const test::FocusedCapture& c = test::galileanCapture();
  FocusedRenderRequest request;
  request.pixelsPerLens = test::kFocusedPixelsPerLens;
  request.virtualDepthMap = &c.truth.virtualDepth;
  auto photo = renderFocused(c.image, c.calibration, request);
  ASSERT_TRUE(photo) << photo.error().message;
  const double db = test::psnr(*photo, c.truth.allInFocus, int(test::kFocusedPixelsPerLens));
  std::printf("total focus with the true virtual depths: PSNR %.2f dB\n", db);
  EXPECT_GT(db, 30);
}

TEST(FocusedRender, TotalFocusFromEstimatedDepthsHasNoSeamsWhereFixedPatchesDo) {
  const test::FocusedCapture& c = test::galileanCapture();
  FocusedDepthRequest depthRequest;
  depthRequest.pixelsPerLens = test::kFocusedPixelsPerLens;
  auto depth = estimateFocusedDepth(c.image, c.calibration, depthRequest);
  ASSERT_TRUE(depth) << depth.error().message;
  FocusedRenderRequest request;
  request.pixelsPerLens = test::kFocusedPixelsPerLens;
  request.virtualDepthMap = &depth->virtualDepth;
  auto totalFocus = renderFocused(c.image, c.calibration, request);
  ASSERT_TRUE(totalFocus) << totalFocus.error().message;
  // Lumsdaine and Georgiev's patches, sized for the middle layer.
  request.virtualDepthMap = nullptr;
  request.virtualDepth = 4.6;
  request.nearestLensOnly = true;
  auto patches = renderFocused(c.image, c.calibration, request);
  ASSERT_TRUE(patches) << patches.error().message;
  const int margin = int(test::kFocusedPixelsPerLens);
  const double ppl = test::kFocusedPixelsPerLens;
  const double ideal = seamEnergy(c.truth.allInFocus, c.calibration, ppl);
  const double seamsTotalFocus = seamEnergy(*totalFocus, c.calibration, ppl) / ideal;
  const double seamsPatches = seamEnergy(*patches, c.calibration, ppl) / ideal;
  const double errorTotalFocus = test::seamError(*totalFocus, c.truth.allInFocus, c.calibration, ppl);
  const double errorPatches = test::seamError(*patches, c.truth.allInFocus, c.calibration, ppl);
  std::printf(
      "total focus from estimated depths: PSNR %.2f dB, seam energy %.2f x the ideal's, seam error %.3f; fixed "
      "patches: PSNR %.2f dB, seam energy %.2f x, seam error %.3f\n",
      test::psnr(*totalFocus, c.truth.allInFocus, margin), seamsTotalFocus, errorTotalFocus,
      test::psnr(*patches, c.truth.allInFocus, margin), seamsPatches, errorPatches);
  EXPECT_GT(test::psnr(*totalFocus, c.truth.allInFocus, margin), 28);
  // No more power at the lattice's frequencies than the ideal's own, and, as errors (the ideal
  // scores 0), at most a tenth of the patches'. (Seam energy over the ideal's grows with sharpness:
  // the ideal itself scores 1 there, 0.14 of the patches'.)
  EXPECT_LT(seamsTotalFocus, 1);
  EXPECT_LT(errorTotalFocus, 0.1 * errorPatches);
}

}  // namespace
}  // namespace lfcam
