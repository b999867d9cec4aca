// The real Raytrix R42 crop (../shared/data/focused-raytrix-r42): its RayCalibData read as
// PlenopticToolbox 2.0 reads it is the grid the micro-images agree on best, its lens types are
// sharp where it says, and its total focus shows no seams where fixed patches do.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lfcam/focused/focused_capture.hpp"
#include "lfcam/focused/focused_depth.hpp"
#include "lfcam/focused/focused_render.hpp"
#include "lfcam/focused/micro_image_sharpness.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

constexpr double kPixelsPerLens = 5;

double meanConfidence(const FocusedCapture& capture, const FocusedCalibration& calibration) {
  FocusedDepthRequest request;
  request.pixelsPerLens = kPixelsPerLens;
  auto depth = estimateFocusedDepth(capture.image, calibration, request);
  EXPECT_TRUE(depth) << depth.error().message;
  double sum = 0;
  for (const float c : depth->confidence.pixels()) sum += c;
  return sum / double(depth->confidence.pixels().size());
}

TEST(RaytrixR42, ItsCalibrationIsTheGridTheMicroImagesAgreeOn) {
  LFCAM_REQUIRE_SHARED_DATA("focused-raytrix-r42", folder);
  auto capture = readFocusedCapture(folder / "sc2_klein.png");
  ASSERT_TRUE(capture) << capture.error().message;
  EXPECT_EQ(capture->calibrationPath.filename(), "sc2_klein.xml");
  const FocusedCalibration& xml = capture->calibration;
  EXPECT_EQ(xml.grid.packing, Packing::Hexagonal);
  EXPECT_EQ(xml.lensTypes.size(), 3u);
  const double agreed = meanConfidence(*capture, xml);
  // The same lattice elsewhere: y read downwards (the reference lens mirrored about the centre),
  // a third of a lens aside, half a lens aside.
  const auto reference = xml.grid.latticeCentre(xml.referenceLens[0], xml.referenceLens[1]);
  const double d = xml.diameterPx();
  for (const auto& [name, centre] : std::initializer_list<std::pair<const char*, std::array<double, 2>>>{
           {"y downwards", {reference[0], xml.imageHeight - reference[1]}},
           {"a third of a lens down", {reference[0], reference[1] + d / 3}},
           {"half a lens right", {reference[0] + d / 2, reference[1]}}}) {
    FocusedCalibration moved =
        focusedGrid(centre, d, Packing::Hexagonal, xml.grid.rotationRad, xml.imageWidth, xml.imageHeight);
    moved.borderPx = xml.borderPx;
    moved.lensTypes = xml.lensTypes;
    const double other = meanConfidence(*capture, moved);
    std::printf("mean confidence: %.3f with the XML's grid, %.3f with it %s\n", agreed, other, name);
    EXPECT_GT(agreed, other + 0.05) << name;
  }
}

// The crop is devignetted (Raytrix's software divides by the white): its lenses do not show where
// they are, and what they show repeats at D (1 - 1 / v), not at D. Calibrating it from itself is
// refused, saying why, rather than a wrong lattice returned.
TEST(RaytrixR42, WithoutItsCalibrationTheDevignettedCropIsRefusedNotMiscalibrated) {
  LFCAM_REQUIRE_SHARED_DATA("focused-raytrix-r42", folder);
  test::TempDir dir;
  std::filesystem::copy_file(folder / "sc2_klein.png", dir / "sc2_klein.png");
  auto capture = readFocusedCapture(dir / "sc2_klein.png", {.calibrateIfNone = true});
  ASSERT_FALSE(capture);
  EXPECT_NE(capture.error().message.find("devignetted?"), std::string::npos) << capture.error().message;
  EXPECT_NE(capture.error().message.find("sc2_klein.png"), std::string::npos) << capture.error().message;
}

TEST(RaytrixR42, LensTypesAreSharpWhereItsCalibrationSays) {
  LFCAM_REQUIRE_SHARED_DATA("focused-raytrix-r42", folder);
  auto capture = readFocusedCapture(folder / "sc2_klein.png");
  ASSERT_TRUE(capture) << capture.error().message;
  const FocusedCalibration& c = capture->calibration;
  FocusedDepthRequest request;
  request.pixelsPerLens = kPixelsPerLens;
  auto depth = estimateFocusedDepth(capture->image, c, request);
  ASSERT_TRUE(depth) << depth.error().message;
  const std::vector<float> sharpness = microImageSharpness(capture->image, c);
  // Most of the scene lies beyond virtual depth 4, in type 2's range (3.8 to 100): there its micro-
  // images are the sharpest, type 0's (1 to 3) the least sharp, judged by their medians.
  std::vector<float> byType[3];
  for (int j = 0; j < c.grid.rows; ++j)
    for (int i = 0; i < c.grid.columns; ++i) {
      const std::size_t k = std::size_t(j) * c.grid.columns + i;
      if (sharpness[k] > 0 && depth->lensVirtualDepth[k] >= 4) byType[c.lensType(i, j)].push_back(sharpness[k]);
    }
  double median[3];
  for (int t = 0; t < 3; ++t) {
    ASSERT_GE(byType[t].size(), 40u) << "type " << t;
    std::nth_element(byType[t].begin(), byType[t].begin() + byType[t].size() / 2, byType[t].end());
    median[t] = byType[t][byType[t].size() / 2];
  }
  std::printf("micro-images at virtual depth >= 4, median sharpness: type 0 %.3f, type 1 %.3f, type 2 %.3f\n",
              median[0], median[1], median[2]);
  EXPECT_GT(median[2], median[1]);
  EXPECT_GT(median[1], median[0]);
}

// Seams without an ideal photograph to compare with: the mean gradient magnitude of the photograph
// on the boundaries between the micro-images' cells (pixels whose right or lower neighbour is
// nearer another micro-image) over that inside them; about 1 where nothing marks the lattice.
double boundaryEdgeRatio(const Image& photo, const FocusedCalibration& calibration, double pixelsPerLens) {
  const LensletGrid& grid = calibration.grid;
  const double scale = calibration.diameterPx() / pixelsPerLens, half = 0.5 * calibration.diameterPx();
  auto nearest = [&](int x, int y) {
    const double qx = half + (x + 0.5) * scale, qy = half + (y + 0.5) * scale;
    const int j0 = int(std::round((qy - grid.origin[1]) / grid.pitchY));
    int best = -1;
    double bestDistance = 1e300;
    for (int j = j0 - 1; j <= j0 + 1; ++j) {
      const int i0 = int(std::round((qx - grid.origin[0]) / grid.pitchX));
      for (int i = i0 - 1; i <= i0 + 1; ++i) {
        const auto c = grid.latticeCentre(i, j);
        const double d = std::hypot(qx - c[0], qy - c[1]);
        if (d < bestDistance) bestDistance = d, best = j * 100000 + i;
      }
    }
    return best;
  };
  double boundary = 0, inside = 0;
  int boundaryCount = 0, insideCount = 0;
  for (int y = 1; y + 1 < photo.height(); ++y)
    for (int x = 1; x + 1 < photo.width(); ++x) {
      double gradient = 0;
      for (int c = 0; c < photo.channels(); ++c)
        gradient += std::hypot(photo.at(x + 1, y, c) - photo.at(x, y, c), photo.at(x, y + 1, c) - photo.at(x, y, c));
      const int here = nearest(x, y);
      if (nearest(x + 1, y) != here || nearest(x, y + 1) != here) {
        boundary += gradient;
        ++boundaryCount;
      } else {
        inside += gradient;
        ++insideCount;
      }
    }
  return (boundary / boundaryCount) / (inside / insideCount);
}

TEST(RaytrixR42, TotalFocusHasNoSeamsWhereFixedPatchesDo) {
  LFCAM_REQUIRE_SHARED_DATA("focused-raytrix-r42", folder);
  auto capture = readFocusedCapture(folder / "sc2_klein.png");
  ASSERT_TRUE(capture) << capture.error().message;
  const double pixelsPerLens = 9;
  FocusedDepthRequest depthRequest;
  depthRequest.pixelsPerLens = pixelsPerLens;
  auto depth = estimateFocusedDepth(capture->image, capture->calibration, depthRequest);
  ASSERT_TRUE(depth) << depth.error().message;
  FocusedRenderRequest request;
  request.pixelsPerLens = pixelsPerLens;
  request.virtualDepthMap = &depth->virtualDepth;
  auto totalFocus = renderFocused(capture->image, capture->calibration, request);
  ASSERT_TRUE(totalFocus) << totalFocus.error().message;
  request.virtualDepthMap = nullptr;
  request.virtualDepth = 5;
  request.nearestLensOnly = true;
  auto patches = renderFocused(capture->image, capture->calibration, request);
  ASSERT_TRUE(patches) << patches.error().message;
  // The woven fabric of this scene repeats at nearly the lattice's period, so the lattice period's
  // power (seamEnergy) reads the scene as much as the seams; the cells' boundaries are read instead.
  const double totalFocusRatio = boundaryEdgeRatio(*totalFocus, capture->calibration, pixelsPerLens);
  const double patchesRatio = boundaryEdgeRatio(*patches, capture->calibration, pixelsPerLens);
  std::printf(
      "gradient on the cells' boundaries over inside them: total focus %.3f, fixed patches of virtual "
      "depth 5 %.3f\n",
      totalFocusRatio, patchesRatio);
  EXPECT_LT(totalFocusRatio, 1.1);
  EXPECT_GT(patchesRatio, 1.3);
}

}  // namespace
}  // namespace lfcam
