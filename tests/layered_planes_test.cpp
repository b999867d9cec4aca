// The layered-planes light field: deterministic, true to its ground truth, and consistent with
// refocusing (each card comes into focus at its own disparity, and only there do the views
// agree on it).
#include "lfcam/synth/layered_planes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "lfcam/render/refocus.hpp"

namespace lfcam {
namespace {

// The default scene, rendered once for every test that needs it (about 2 s of CPU).
const LayeredPlanesLightField& defaultScene() {
  static const LayeredPlanesLightField rendered = renderLayeredPlanes(defaultLayeredPlanesScene());
  return rendered;
}

LayeredPlanesScene smallScene(std::uint64_t seed) {
  LayeredPlanesScene scene = defaultLayeredPlanesScene();
  for (TexturedPlane& plane : scene.planes) plane.x0 /= 4, plane.y0 /= 4, plane.x1 /= 4, plane.y1 /= 4;
  scene.nu = 5, scene.nv = 4, scene.ns = 64, scene.nt = 48;
  scene.seed = seed;
  return scene;
}

// Pixels whose ground truth is `disparity` and whose whole (2 margin + 1)^2 neighbourhood is too.
std::vector<std::pair<int, int>> region(const Image& truth, double disparity, int margin) {
  std::vector<std::pair<int, int>> pixels;
  for (int t = margin; t < truth.height() - margin; ++t)
    for (int s = margin; s < truth.width() - margin; ++s) {
      bool all = true;
      for (int dt = -margin; dt <= margin && all; ++dt)
        for (int ds = -margin; ds <= margin && all; ++ds) all = truth.at(s + ds, t + dt, 0) == float(disparity);
      if (all) pixels.emplace_back(s, t);
    }
  return pixels;
}

// Variance of the Laplacian of the photo's luminance over `pixels`: a standard focus measure.
double laplacianVariance(const Image& photo, const std::vector<std::pair<int, int>>& pixels) {
  auto luminance = [&](int s, int t) {
    double sum = 0;
    for (int c = 0; c < photo.channels(); ++c) sum += photo.at(s, t, c);
    return sum / photo.channels();
  };
  double sum = 0, sumSquares = 0;
  for (auto [s, t] : pixels) {
    const double laplacian =
        luminance(s - 1, t) + luminance(s + 1, t) + luminance(s, t - 1) + luminance(s, t + 1) - 4 * luminance(s, t);
    sum += laplacian, sumSquares += laplacian * laplacian;
  }
  const double mean = sum / pixels.size();
  return sumSquares / pixels.size() - mean * mean;
}

// Mean over `pixels` of the variance across views of what each view sees at (s - u d, t - v d)
// (bilinear): zero when every view sees the same point of a surface of disparity d.
double varianceAcrossViews(const LightField& lightField, double d, const std::vector<std::pair<int, int>>& pixels) {
  auto sample = [&](int u, int v, double x, double y, int c) {
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double ax = x - x0, ay = y - y0;
    auto at = [&](int s, int t) {
      return double(
          lightField.at(u, v, std::clamp(s, 0, lightField.ns() - 1), std::clamp(t, 0, lightField.nt() - 1), c));
    };
    return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) +
           ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
  };
  double total = 0;
  for (auto [s, t] : pixels)
    for (int c = 0; c < lightField.channels(); ++c) {
      double sum = 0, sumSquares = 0;
      for (int v = 0; v < lightField.nv(); ++v)
        for (int u = 0; u < lightField.nu(); ++u) {
          const double value = sample(u, v, s - lightField.uFromCentre(u) * d, t - lightField.vFromCentre(v) * d, c);
          sum += value, sumSquares += value * value;
        }
      const double n = lightField.nu() * lightField.nv();
      total += sumSquares / n - (sum / n) * (sum / n);
    }
  return total / (pixels.size() * lightField.channels());
}

TEST(LayeredPlanes, IsDeterministicForASeed) {
  const LayeredPlanesLightField first = renderLayeredPlanes(smallScene(4));
  const LayeredPlanesLightField second = renderLayeredPlanes(smallScene(4));
  const LayeredPlanesLightField other = renderLayeredPlanes(smallScene(5));
  ASSERT_EQ(first.lightField.shape(), (LightFieldShape{.nu = 5, .nv = 4, .ns = 64, .nt = 48, .channels = 3}));
  EXPECT_TRUE(std::ranges::equal(first.lightField.samples(), second.lightField.samples()));
  EXPECT_TRUE(std::ranges::equal(first.disparity.pixels(), second.disparity.pixels()));
  EXPECT_FALSE(std::ranges::equal(first.lightField.samples(), other.lightField.samples()));
  EXPECT_EQ(first.lightField.metadata.source, "lfcam layered planes, seed 4");
}

TEST(LayeredPlanes, DefaultSceneHasFourPlanesAndPlausibleOptics) {
  const LayeredPlanesScene scene = defaultLayeredPlanesScene();
  EXPECT_EQ(scene.nu, 9);
  EXPECT_EQ(scene.ns, 256);
  ASSERT_EQ(scene.planes.size(), 4u);
  const LightField& lightField = defaultScene().lightField;
  ASSERT_TRUE(lightField.metadata.optics.has_value());
  EXPECT_GT(lightField.metadata.optics->lensStepMm, 0);
  EXPECT_NEAR(lightField.metadata.optics->slopeFromAlpha(1.0), 0.0, 1e-12);
  EXPECT_EQ(lightField.metadata.disparityMin, -1.0);
  EXPECT_EQ(lightField.metadata.disparityMax, 1.6);
  // Linear values in a photographic range.
  auto [lowest, highest] = std::ranges::minmax(lightField.samples());
  EXPECT_GE(lowest, 0.02f);
  EXPECT_LE(highest, 0.9f);
}

TEST(LayeredPlanes, DisparityImageHoldsThePlaneDisparities) {
  const LayeredPlanesScene scene = defaultLayeredPlanesScene();
  const Image& truth = defaultScene().disparity;
  ASSERT_EQ(truth.width(), 256);
  ASSERT_EQ(truth.channels(), 1);
  std::set<float> expected, seen;
  for (const TexturedPlane& plane : scene.planes) expected.insert(float(plane.disparity));
  for (float d : truth.pixels()) seen.insert(d);
  EXPECT_EQ(seen, expected);  // each plane is visible somewhere, and nothing else appears
  // Each card's own pixel at its centre, unless a nearer card covers it; the background at the
  // corners.
  EXPECT_EQ(truth.at(0, 0, 0), -1.0f);
  EXPECT_EQ(truth.at(255, 255, 0), -1.0f);
  for (const TexturedPlane& plane : scene.planes) {
    if (plane.x1 <= plane.x0) continue;
    const int s = int(0.5 * (plane.x0 + plane.x1)), t = int(0.5 * (plane.y0 + plane.y1));
    EXPECT_EQ(truth.at(s, t, 0), float(plane.disparity)) << "card at disparity " << plane.disparity;
  }
}

TEST(LayeredPlanes, ASurfaceMovesByMinusVDBetweenViewsAndHidesWhatIsBehind) {
  // The red card (disparity 1.6, rows [160, 232) in the centre view) appears in view row v
  // displaced by -v d (light_field.hpp): its top edge at 160 + 6.4 in the top view (v = -4) and
  // at 160 - 6.4 in the bottom view (v = +4), covering the background there.
  const LightField& lightField = defaultScene().lightField;
  const int column = 100;  // u = 0: inside the card, away from the other cards
  auto redRows = [&](int v) {
    int rows = 0;
    for (int t = 140; t < 180; ++t)  // red minus green: > 0 on the card only
      rows += lightField.at(4, v, column, t, 0) - lightField.at(4, v, column, t, 1) > 0;
    return rows;
  };
  EXPECT_NEAR(redRows(0), 180 - 166.4, 1.0);
  EXPECT_NEAR(redRows(8), 180 - 153.6, 1.0);
}

TEST(LayeredPlanes, EachCardIsSharpestAtItsOwnDisparity) {
  const LayeredPlanesScene scene = defaultLayeredPlanesScene();
  const LayeredPlanesLightField& rendered = defaultScene();
  for (const TexturedPlane& card : scene.planes) {
    if (card.x1 <= card.x0) continue;  // the background
    // Away from every edge by more than the largest relative shift (4 views x 2.6 px).
    const auto pixels = region(rendered.disparity, card.disparity, 12);
    ASSERT_GT(pixels.size(), 500u) << "card at " << card.disparity;
    const double inFocus = laplacianVariance(refocus(rendered.lightField, card.disparity), pixels);
    for (const TexturedPlane& other : scene.planes) {
      if (other.disparity == card.disparity) continue;
      const double outOfFocus = laplacianVariance(refocus(rendered.lightField, other.disparity), pixels);
      EXPECT_GT(inFocus, 2.5 * outOfFocus) << "card at " << card.disparity << ", focused at " << other.disparity;
    }
  }
}

TEST(LayeredPlanes, ViewsAgreeOnACardAtItsDisparity) {
  const LayeredPlanesScene scene = defaultLayeredPlanesScene();
  const LayeredPlanesLightField& rendered = defaultScene();
  for (const TexturedPlane& card : scene.planes) {
    if (card.x1 <= card.x0) continue;
    const auto pixels = region(rendered.disparity, card.disparity, 12);
    const double atOwn = varianceAcrossViews(rendered.lightField, card.disparity, pixels);
    const double elsewhere = varianceAcrossViews(rendered.lightField, card.disparity + 0.5, pixels);
    EXPECT_LT(atOwn, 2e-4) << "card at " << card.disparity;
    EXPECT_LT(atOwn, 0.05 * elsewhere) << "card at " << card.disparity;
    if (card.disparity == std::round(card.disparity)) {
      EXPECT_LT(atOwn, 1e-12) << "whole-pixel shifts are exact";
    }
  }
}

}  // namespace
}  // namespace lfcam
