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
  const double ideal = seamEnergy(c.truth.allInFocus, c.calibration, test::kFocusedPixelsPerLens);
  const double seamsTotalFocus = seamEnergy(*totalFocus, c.calibration, test::kFocusedPixelsPerLens) / ideal;
  const double seamsPatches = seamEnergy(*patches, c.calibration, test::kFocusedPixelsPerLens) / ideal;
  std::printf(
      "total focus from estimated depths: PSNR %.2f dB, seam energy %.2f x the ideal's; fixed patches: "
      "PSNR %.2f dB, seam energy %.2f x\n",
      test::psnr(*totalFocus, c.truth.allInFocus, margin), seamsTotalFocus,
      test::psnr(*patches, c.truth.allInFocus, margin), seamsPatches);
  EXPECT_GT(test::psnr(*totalFocus, c.truth.allInFocus, margin), 28);
  // No more power at the lattice's frequencies than the ideal's own. The measure also grows with
  // sharpness (the ideal under a [1 2 1] / 4 blur scores 0.46-0.96 of itself): the ideal itself
  // would score 1, 0.14 of fixed patches' 7.05, so a tenth holds only a blurred total focus.
  EXPECT_LT(seamsTotalFocus, 1);
  EXPECT_LT(seamsTotalFocus, 0.15 * seamsPatches);
}

}  // namespace
}  // namespace lfcam
