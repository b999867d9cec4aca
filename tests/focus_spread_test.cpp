// Focus spread (focus_spread.hpp): the slope-field kernel with a tap test against the float64
// oracle; on the layered planes, every surface in the range sharp, the blur outside it a lens's,
// and no ghost of a sharp near card over the blurred surfaces beside it; bad ranges refused.
#include "lfcam/render/focus_spread.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "lfcam/edof/depth.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "random_light_field.hpp"
#include "render/references.hpp"
#include "render/slope_field_rows.hpp"

namespace lfcam {
namespace {

// A slope per pixel of `lightField`, each drawn in [-2.5, 2.5].
struct RandomSlopes {
  RandomSlopes(const LightField& lightField, std::mt19937& random) : ns(lightField.ns()) {
    std::uniform_real_distribution<double> anySlope(-2.5, 2.5);
    slopes.resize(std::size_t(ns) * lightField.nt());
    for (double& slope : slopes) slope = anySlope(random);
  }
  double operator()(int x, int y) const { return slopes[std::size_t(y) * ns + x]; }
  int ns;
  std::vector<double> slopes;
};

TEST(FocusSpread, SlopeFieldKernelWithATapTestMatchesTheReference) {
  std::mt19937 random(2005);
  for (int trial = 0; trial < 30; ++trial) {
    const LightField lightField = test::randomTrialLightField(random, trial, 6, 37);
    const RandomSlopes slopeAt(lightField, random);
    // A tap test that depends on every argument.
    auto keep = [](int u, int v, int row, int column, int x, int y) {
      return (u * 7 + v * 5 + row * 3 + column + x * 11 + y * 13) % 4 != 0;
    };
    const Image fast = refocusSlopeField(lightField, slopeAt, keep);
    const Image reference = refocusSlopeFieldReference(lightField, slopeAt, keep);
    EXPECT_LT(test::worstRelativeError(fast, reference), 1e-5) << "trial " << trial;
  }
}

// A pixel whose every ray the tap test leaves out (an estimated map that puts it behind every
// surface its rays meet) is rendered from all its rays, not left black.
TEST(FocusSpread, APixelWhoseEveryRayIsLeftOutTakesThemAll) {
  std::mt19937 random(2006);
  for (int trial = 0; trial < 10; ++trial) {
    const LightField lightField = test::randomTrialLightField(random, trial, 6, 29);
    const int ns = lightField.ns();
    const RandomSlopes slopeAt(lightField, random);
    auto keep = [](int, int, int, int, int x, int y) { return (x + y) % 3 != 0; };
    const Image fast = refocusSlopeField(lightField, slopeAt, keep);
    const Image everyRay = refocusSlopeField(lightField, slopeAt);
    EXPECT_LT(test::worstRelativeError(fast, refocusSlopeFieldReference(lightField, slopeAt, keep)), 1e-5);
    for (int y = 0; y < lightField.nt(); ++y)
      for (int x = (3 - y % 3) % 3; x < ns; x += 3)
        for (int c = 0; c < lightField.channels(); ++c)
          ASSERT_NEAR(fast.at(x, y, c), everyRay.at(x, y, c), 1e-6 + 1e-5 * std::abs(everyRay.at(x, y, c)))
              << "trial " << trial << ", pixel " << x << "," << y;
  }
}

// The layered planes (a cloudy background at -1, cards at 0, 0.8 and 1.6), and the same with the
// nearest card tinted darker: a pixel whose photograph changes with the tint holds the card's light.
struct Scenes {
  LayeredPlanesLightField scene, tinted;
};

Scenes layeredPlanes() {
  LayeredPlanesScene scene = defaultLayeredPlanesScene(9, 128);
  Scenes scenes{renderLayeredPlanes(scene), {}};
  auto nearest = std::max_element(scene.planes.begin(), scene.planes.end(),
                                  [](const auto& a, const auto& b) { return a.disparity < b.disparity; });
  for (float& c : nearest->colour) c *= 0.5f;
  scenes.tinted = renderLayeredPlanes(scene);
  return scenes;
}

float pixelDifference(const Image& a, const Image& b, int x, int y) {
  float worst = 0;
  for (int c = 0; c < a.channels(); ++c) worst = std::max(worst, std::abs(a.at(x, y, c) - b.at(x, y, c)));
  return worst;
}

// The pixels off the near card (truth below 1.5) that hold its light (their photograph changes with
// the card's tint), counted by their chessboard distance from the card (index 0: distance 1, ...).
std::vector<int> ghostByDistance(const Image& photo, const Image& tintedPhoto, const Image& truth, int reach) {
  const int w = truth.width(), h = truth.height();
  std::vector<int> counts(reach, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (truth.at(x, y, 0) > 1.5f) continue;
      int distance = reach + 1;
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx >= 0 && xx < w && yy >= 0 && yy < h && truth.at(xx, yy, 0) > 1.5f)
            distance = std::min(distance, std::max(std::abs(dx), std::abs(dy)));
        }
      if (distance <= reach && pixelDifference(photo, tintedPhoto, x, y) > 1e-3f) ++counts[distance - 1];
    }
  return counts;
}

int beyondTwoPixels(const std::vector<int>& counts, const char* what) {
  int beyond = 0;
  std::printf("pixels holding the near card's light at 1..%zu px from it, %s:", counts.size(), what);
  for (std::size_t i = 0; i < counts.size(); ++i) std::printf(" %d", counts[i]), beyond += i >= 2 ? counts[i] : 0;
  std::printf("\n");
  return beyond;
}

TEST(FocusSpread, NearCardSharpWithNoGhostOverTheBlurredSurfacesBesideIt) {
  const Scenes scenes = layeredPlanes();
  const LightField& lightField = scenes.scene.lightField;
  const Image& truth = scenes.scene.disparity;
  // In focus from the middle card (0.8) to the near card (1.6): the card at 0 and the background are
  // rendered at 0.8, as a lens focused on the middle card renders them.
  auto spread = refocusSpread(lightField, truth, 0.8, 1.6);
  auto tinted = refocusSpread(scenes.tinted.lightField, truth, 0.8, 1.6);
  ASSERT_TRUE(spread && tinted) << spread.error().message;
  EXPECT_EQ(beyondTwoPixels(ghostByDistance(*spread, *tinted, truth, 8), "focus spread"), 0);
  // Without leaving the near card's rays out, at the same slopes: its ghost over its surroundings,
  // as far as the outer views' rays reach (4 views x (1.6 - 0.8) = 3.2 px), so the test can fail.
  const float* map = truth.plane(0);
  const int ns = lightField.ns();
  auto slopeAt = [&](int x, int y) { return std::clamp(double(map[y * ns + x]), 0.8, 1.6); };
  const Image ghosted = refocusSlopeField(lightField, slopeAt),
              ghostedTinted = refocusSlopeField(scenes.tinted.lightField, slopeAt);
  EXPECT_GT(beyondTwoPixels(ghostByDistance(ghosted, ghostedTinted, truth, 8), "all rays"), 100);

  // Every surface in the range is sharp: each card as refocused at its own slope; below the range
  // (the card at 0, the background), the blur of a lens focused at 0.8. Away from edges (8 px: the
  // background's blur reaches 4 x 1.8 px), where only one surface's rays arrive.
  const Image nearFocus = refocus(lightField, 1.6), middleFocus = refocus(lightField, 0.8);
  double worst = 0;
  for (int y = 8; y < truth.height() - 8; ++y)
    for (int x = 8; x < truth.width() - 8; ++x) {
      const float d = truth.at(x, y, 0);
      bool interior = true;
      for (int dy = -8; dy <= 8 && interior; ++dy)
        for (int dx = -8; dx <= 8 && interior; ++dx) interior = truth.at(x + dx, y + dy, 0) == d;
      if (interior) worst = std::max(worst, double(pixelDifference(*spread, d > 1.5f ? nearFocus : middleFocus, x, y)));
    }
  EXPECT_LT(worst, 1e-4);
}

TEST(FocusSpread, EstimatedDepthLeavesNoGhostRingEither) {
  const Scenes scenes = layeredPlanes();
  auto depth = estimateDepth(scenes.scene.lightField);
  ASSERT_TRUE(depth);
  auto spread = refocusSpread(scenes.scene.lightField, depth->disparity, 0.8, 1.6);
  auto tinted = refocusSpread(scenes.tinted.lightField, depth->disparity, 0.8, 1.6);
  ASSERT_TRUE(spread && tinted);
  EXPECT_LT(beyondTwoPixels(ghostByDistance(*spread, *tinted, scenes.scene.disparity, 8), "estimated depth"), 20);
}

TEST(FocusSpread, BadRangesAndMapsAreUsageErrors) {
  std::mt19937 random(3);
  const LightField lightField =
      test::randomLightField({.nu = 3, .nv = 3, .ns = 16, .nt = 12, .channels = 1}, random, false);
  const Image map(16, 12, 1);
  auto behind = refocusSpread(lightField, map, 1.0, 0.5);
  ASSERT_FALSE(behind);
  EXPECT_EQ(behind.error().code, ErrorCode::Usage);
  EXPECT_NE(behind.error().message.find("behind"), std::string::npos) << behind.error().message;
  EXPECT_FALSE(refocusSpread(lightField, Image(15, 12, 1), 0, 1));
  Image notFinite(16, 12, 1);
  notFinite.at(3, 4, 0) = NAN;
  EXPECT_FALSE(refocusSpread(lightField, notFinite, 0, 1));
  // A range of one slope is a plain refocus wherever nothing nearer occludes.
  auto same = refocusSpread(lightField, map, 0.0, 0.0);
  ASSERT_TRUE(same);
  EXPECT_LT(test::worstRelativeError(*same, refocus(lightField, 0.0)), 1e-5);
}

}  // namespace
}  // namespace lfcam
