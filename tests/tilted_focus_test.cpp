// refocusTilted (fast, float32) against refocusTiltedReference (float64 oracle); the plane from
// three points or a tilt; and on a simulated slanted plane, the tilted photograph is sharp along
// the whole plane where every fronto-parallel refocus blurs part of it.
#include "lfcam/render/tilted_focus.hpp"
#include "render/references.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "lfcam/edof/depth.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "people_camera.hpp"
#include "random_light_field.hpp"
#include "sharpness.hpp"

namespace lfcam {
namespace {

using test::randomLightField;
using test::worstRelativeError;  // against the float64 oracle

TEST(TiltedFocus, FastMatchesReferenceOnRandomLightFieldsAndPlanes) {
  std::mt19937 random(19041904);
  std::uniform_real_distribution<double> anySlope(-3.0, 3.0), anyGradient(-0.2, 0.2), anyCentre(-5.0, 45.0);
  for (int trial = 0; trial < 40; ++trial) {
    const LightField lightField = test::randomTrialLightField(random, trial, 6, 41);
    const LightFieldShape& shape = lightField.shape();
    for (int planeIndex = 0; planeIndex < 4; ++planeIndex) {
      FocusPlane plane{.slope = anySlope(random),
                       .gradientX = anyGradient(random),
                       .gradientY = anyGradient(random),
                       .centreX = anyCentre(random),
                       .centreY = anyCentre(random)};
      if (planeIndex == 3) plane.gradientX = 2.0;  // slopes so large that the outer views leave the image
      const Image fast = refocusTilted(lightField, plane);
      ASSERT_EQ(fast.width(), shape.ns);
      ASSERT_EQ(fast.height(), shape.nt);
      ASSERT_EQ(fast.channels(), shape.channels);
      EXPECT_LT(worstRelativeError(fast, refocusTiltedReference(lightField, plane)), 1e-5)
          << "views " << shape.nu << "x" << shape.nv << ", pixels " << shape.ns << "x" << shape.nt
          << (lightField.hasWeight() ? ", weighted" : "") << ", slope " << plane.slope << ", gradient "
          << plane.gradientX << "," << plane.gradientY;
    }
  }
}

TEST(TiltedFocus, AFrontoParallelPlaneIsRefocus) {
  std::mt19937 random(5);
  const LightField lightField = randomLightField({.nu = 5, .nv = 4, .ns = 83, .nt = 61, .channels = 3}, random, true);
  const FocusPlane plane = focusPlaneFromTilt(lightField, 1.25, 0.0, 30.0);
  EXPECT_LT(worstRelativeError(refocusTilted(lightField, plane), refocus(lightField, 1.25)), 1e-5);
}

TEST(TiltedFocus, TiltIsTheSlopeChangeOverOneImageWidth) {
  std::mt19937 random(6);
  const LightField lightField = randomLightField({.nu = 3, .nv = 3, .ns = 100, .nt = 50, .channels = 1}, random, false);
  const FocusPlane right = focusPlaneFromTilt(lightField, 0.5, 2.0, 0.0);
  EXPECT_NEAR(right.slopeAt(100, 25) - right.slopeAt(0, 25), 2.0, 1e-12);
  EXPECT_NEAR(right.slopeAt(50, 25), 0.5, 1e-12);
  const FocusPlane down = focusPlaneFromTilt(lightField, 0.5, 2.0, 90.0);
  EXPECT_NEAR(down.slopeAt(50, 50) - down.slopeAt(50, 0), 1.0, 1e-12);  // half a width down
  EXPECT_NEAR(down.slopeAt(0, 25) - down.slopeAt(100, 25), 0.0, 1e-12);
}

TEST(TiltedFocus, CollinearOrOutsidePointsAreUsageErrors) {
  std::mt19937 random(7);
  const LightField lightField = randomLightField({.nu = 3, .nv = 3, .ns = 40, .nt = 30, .channels = 1}, random, false);
  const auto collinear = focusPlaneThroughPoints(lightField, {{{2, 2}, {20, 11}, {38, 20.5}}});
  ASSERT_FALSE(collinear);
  EXPECT_EQ(collinear.error().code, ErrorCode::Usage);
  const auto outside = focusPlaneThroughPoints(lightField, {{{2, 2}, {40, 11}, {10, 20}}});
  ASSERT_FALSE(outside);
  EXPECT_EQ(outside.error().code, ErrorCode::Usage);
}

// A textured plane slanted in depth from 0.7 to 1.8 times the focus distance, left to right,
// filling the view of the people test's camera (80x80 microlenses, 9x9 views).
LightField slantedPlaneLightField() {
  const CameraModel camera = test::peopleCamera();
  const double d = camera.mainLens.focusDistanceMm;
  // Half the field of view per mm of distance.
  const double field = 0.5 * camera.sensor.widthMm() / camera.mainLens.imageDistanceMm();
  const double nearZ = 0.7 * d, farZ = 1.8 * d;
  const double leftX = -1.3 * field * nearZ, rightX = 1.3 * field * farZ;
  Scene scene;
  scene.camera = camera;
  Plane plane;
  plane.name = "slanted";
  plane.centreMm = {(leftX + rightX) / 2, 0, (nearZ + farZ) / 2};
  plane.widthMm = std::hypot(rightX - leftX, farZ - nearZ);
  plane.heightMm = 2.6 * field * farZ;
  plane.tiltYDeg = std::atan2(farZ - nearZ, rightX - leftX) * 180 / M_PI;  // its right side away
  plane.texture.kind = TextureKind::Noise;
  plane.texture.periodMm = field * d / 6;
  plane.texture.seed = 3;
  scene.planes.push_back(plane);
  auto lightField = idealLightFieldBoxFiltered(scene, camera, 2);  // as the sensor samples it: no aliasing
  EXPECT_TRUE(lightField) << lightField.error().message;
  return std::move(*lightField);
}

TEST(TiltedFocus, SharpAlongASlantedPlaneWhereEveryFrontoParallelFocusBlursPartOfIt) {
  const LightField lightField = slantedPlaneLightField();
  const int ns = lightField.ns(), nt = lightField.nt();
  // Four strips across the image, from the near (left) to the far (right) end of the plane.
  const int strips = 4, margin = ns / 10, stripWidth = (ns - 2 * margin) / strips;
  const auto sharpness = [&](const Image& photo) {
    std::vector<double> perStrip;
    for (int i = 0; i < strips; ++i)
      perStrip.push_back(
          test::laplacianVariance(photo, margin + i * stripWidth, margin, margin + (i + 1) * stripWidth, nt - margin));
    return perStrip;
  };

  // The plane's disparities, and beyond.
  const Optics& optics = *lightField.metadata.optics;
  const double d = test::peopleCamera().mainLens.focusDistanceMm;
  const double nearSlope = *disparityFromDistance(optics, 0.7 * d), farSlope = *disparityFromDistance(optics, 1.8 * d);
  const double low = std::min(nearSlope, farSlope) - 0.3, high = std::max(nearSlope, farSlope) + 0.3;

  auto plane =
      focusPlaneThroughPoints(lightField, {{{0.15 * ns, 0.5 * nt}, {0.85 * ns, 0.2 * nt}, {0.85 * ns, 0.8 * nt}}},
                              {.minSlope = low, .maxSlope = high});
  ASSERT_TRUE(plane) << plane.error().message;
  const std::vector<double> tilted = sharpness(refocusTilted(lightField, *plane));

  // Every fronto-parallel refocus over that range.
  std::vector<double> best(strips, 0.0);
  std::vector<std::vector<double>> fronto;
  for (double slope : evenlySpaced(low, high, 41)) {
    fronto.push_back(sharpness(refocus(lightField, slope)));
    for (int i = 0; i < strips; ++i) best[i] = std::max(best[i], fronto.back()[i]);
  }
  std::printf("plane: slope %.3f at the centre, gradient %.4f, %.4f per pixel (disparities %.3f near, %.3f far)\n",
              plane->slope, plane->gradientX, plane->gradientY, nearSlope, farSlope);
  for (int i = 0; i < strips; ++i) {
    std::printf("strip %d: tilted %.5f, best fronto-parallel %.5f (%.1f %%)\n", i, tilted[i], best[i],
                100 * tilted[i] / best[i]);
    EXPECT_GE(tilted[i], 0.9 * best[i]) << "strip " << i;
  }
  double bestWorstStrip = 0;  // over fronto-parallel photos, the blurriest strip's share of its best
  for (const std::vector<double>& photo : fronto) {
    double worst = 1;
    for (int i = 0; i < strips; ++i) worst = std::min(worst, photo[i] / best[i]);
    bestWorstStrip = std::max(bestWorstStrip, worst);
  }
  std::printf("the best fronto-parallel photo's blurriest strip: %.1f %% of its best\n", 100 * bestWorstStrip);
  EXPECT_LT(bestWorstStrip, 0.9);
}

}  // namespace
}  // namespace lfcam
