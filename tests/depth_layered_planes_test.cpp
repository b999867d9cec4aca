// Depth estimation measured on layered-planes light fields (exact ground truth), the HCI
// benchmark's scores on hand-made maps, distances from disparities, and the colour map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "depth_scenes.hpp"
#include "edof/depth_experiment.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/edof/disparity_scores.hpp"
#include "lfcam/io/color_map.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/synth/layered_planes.hpp"

namespace lfcam {
namespace {

Image constantImage(int size, float value) {
  Image image(size, size, 1);
  for (float& v : image.pixels()) v = value;
  return image;
}

TEST(DisparityScores, CountTheBorderOutAndScoreAsTheBenchmark) {
  const int size = 40;  // 10 x 10 pixels inside a 15-pixel border
  const Image truth = constantImage(size, 1.0f);
  Image estimate = constantImage(size, 1.0f);
  // Inside: 10 pixels off by 0.1 (bad), 10 off by 0.05 (good); outside the border: way off.
  for (int i = 0; i < 10; ++i) estimate.at(15 + i, 15, 0) = 1.1f, estimate.at(15 + i, 16, 0) = 1.05f;
  estimate.at(0, 0, 0) = 100.0f;
  estimate.at(14, 20, 0) = 100.0f;
  auto scores = scoreDisparity(estimate, truth);
  ASSERT_TRUE(scores) << scores.error().message;
  EXPECT_EQ(scores->pixels, 100);
  EXPECT_NEAR(scores->badPix, 10.0, 1e-9);
  EXPECT_NEAR(scores->mse100, 100.0 * (10 * 0.01 + 10 * 0.0025) / 100, 1e-5);
}

TEST(DisparityScores, SkipUnknownTruthAndPenaliseHoles) {
  Image truth = constantImage(32, 0.5f), estimate = constantImage(32, 0.5f);
  truth.at(16, 16, 0) = std::numeric_limits<float>::quiet_NaN();
  estimate.at(15, 16, 0) = std::numeric_limits<float>::quiet_NaN();
  auto scores = scoreDisparity(estimate, truth, 0.07, 15);
  ASSERT_TRUE(scores);
  EXPECT_EQ(scores->pixels, 3);  // 2 x 2 inside, one without truth
  EXPECT_NEAR(scores->badPix, 100.0 / 3, 1e-9);
  EXPECT_FALSE(scoreDisparity(constantImage(8, 0), constantImage(9, 0)));
}

// The default scene (four planes at -1, 0, 0.8, 1.6 with occlusions), 9x9 views of 128x128.
TEST(DepthLayeredPlanes, MeetsTheBenchmarkScoresWithExactTruth) {
  const LayeredPlanesLightField scene = renderLayeredPlanes(defaultLayeredPlanesScene(9, 128));
  auto depth = estimateDepth(scene.lightField);
  ASSERT_TRUE(depth) << depth.error().message;
  EXPECT_DOUBLE_EQ(depth->disparityMin, -1.0);
  EXPECT_DOUBLE_EQ(depth->disparityMax, 1.6);
  auto scores = scoreDisparity(depth->disparity, scene.disparity);
  ASSERT_TRUE(scores);
  std::printf("layered planes 9x9x128x128: BadPix(0.07) %.2f %%, MSE x100 %.3f\n", scores->badPix, scores->mse100);
  // Measured 4.1 % and 6.6 with the defaults chosen on the development scenes (issue 18); 5.5 % and
  // 6.7 with issue 6's, 10.2 % and 8.4 with DepthOptions::occlusionBand 0 (5.6 % and 8.0 before
  // issue 6's sixth round's defaults; 8.6 % and 8.9 before
  // edof::DepthExperiment::aggregateSubsetsApart; 8.4 % and 8.9 before edof::DepthExperiment::refineAggregateHalves;
  // 11.2 % and 9.3 before issue 6's second round: strict half-apertures, defocus weight 0.5,
  // median radius 6, the fine search from the map's local mean).
  EXPECT_LT(scores->badPix, 7.5);
  EXPECT_LT(scores->mse100, 9.0);
  // Confidence is a fraction, and higher on the textured planes than nowhere.
  for (float c : depth->confidence.pixels()) ASSERT_TRUE(c >= 0 && c <= 1);
}

// Bilinear sampling between pixels blurs, so the cost prefers whole-pixel shifts; the bias term
// removed from the cost (edof::DepthExperiment::lockingCorrection) must bring fine-textured planes at
// fractional disparities nearer their truth than without it (measured: mean errors summed over
// the four planes 0.0115 against 0.0153), on views matched as they are: once the views' offsets
// are removed (DepthOptions::offsetRadius, the default) the bias is 0.0023 without the correction
// and 0.0038 with it, which is why it stays an experiment.
TEST(DepthLayeredPlanes, InterpolationBiasCorrectionReducesPixelLocking) {
  auto summedBias = [](double locking) {
    double total = 0;
    for (double truth : {0.25, 0.45, 0.65, 1.35}) {
      LayeredPlanesScene scene = defaultLayeredPlanesScene(9, 64);
      scene.planes.clear();
      TexturedPlane plane;
      plane.disparity = truth;
      plane.texture = PlaneTexture::Noise;
      plane.period = 2;
      scene.planes.push_back(plane);
      const LayeredPlanesLightField rendered = renderLayeredPlanes(scene);
      auto depth =
          edof::estimateDepth(rendered.lightField, {.disparityMin = -1.0, .disparityMax = 1.6, .offsetRadius = 0},
                              {.lockingCorrection = locking});
      EXPECT_TRUE(depth) << depth.error().message;
      if (!depth) return 1e9;
      double sum = 0;
      long count = 0;
      for (int y = 8; y < 56; ++y)
        for (int x = 8; x < 56; ++x) sum += depth->disparity.at(x, y, 0) - truth, ++count;
      total += std::abs(sum / double(count));
    }
    return total;
  };
  const double without = summedBias(0.0), with = summedBias(1.0);
  std::printf("pixel locking: summed mean error %.4f with the correction, %.4f without\n", with, without);
  EXPECT_LT(with, 0.85 * without);
}

// A sheen: every view brighter or darker than the centre view by a gain that changes across the
// aperture (-20 % to +20 % from one corner to the other). Matched as they are, the views disagree
// where the texture is faint; with their offsets removed (DepthOptions::offsetRadius, the default)
// the map must be nearly as good as without the sheen. Measured: BadPix(0.07) 20.2 % as given,
// 4.7 % removed, 4.2 % without sheen.
TEST(DepthLayeredPlanes, ViewOffsetsCancelASheen) {
  LayeredPlanesScene scene = defaultLayeredPlanesScene(9, 96);
  LayeredPlanesLightField plain = renderLayeredPlanes(scene);
  LightField glossy = plain.lightField.copy();
  for (int v = 0; v < glossy.nv(); ++v)
    for (int u = 0; u < glossy.nu(); ++u) {
      const float gain = 1.0f + 0.1f * (float(u - 4) / 4 + float(v - 4) / 4);
      for (int c = 0; c < glossy.channels(); ++c) {
        float* plane = glossy.plane(u, v, c);
        for (std::size_t i = 0; i < glossy.shape().viewPixels(); ++i) plane[i] *= gain;
      }
    }
  const auto badPix = [&](const LightField& lightField, int offsetRadius) {
    auto depth = estimateDepth(lightField, {.offsetRadius = offsetRadius});
    EXPECT_TRUE(depth) << depth.error().message;
    return depth ? scoreDisparity(depth->disparity, plain.disparity)->badPix : 100.0;
  };
  const double matte = badPix(plain.lightField, 16), asGiven = badPix(glossy, 0), removed = badPix(glossy, 16);
  std::printf("sheen: BadPix(0.07) %.2f %% matched as given, %.2f %% with the offsets removed, %.2f %% without sheen\n",
              asGiven, removed, matte);
  EXPECT_GT(asGiven, removed + 5.0);
  EXPECT_LT(removed, matte + 1.0);
}

// Noisy views with regions larger than the windows and no texture but noise (the checkerboard's
// squares, 32 px): bilinear sampling halves the noise variance at half-pixel shifts, so there the
// cost of every disparity that shifts views by half a pixel is lowest. With the noise that
// interpolation removes added back (edof::DepthExperiment::noiseCorrection, the default) the map
// must be better. Measured: BadPix(0.07) 19.23 % with it, 30.23 % without.
TEST(DepthLayeredPlanes, NoiseCorrectionKeepsFlatNoisyRegionsOffHalfPixelShifts) {
  LayeredPlanesScene scene = defaultLayeredPlanesScene(9, 128);
  for (TexturedPlane& plane : scene.planes) plane.period *= 2;
  LayeredPlanesLightField plain = renderLayeredPlanes(scene);
  LightField noisy = plain.lightField.copy();
  std::mt19937 random(7);
  std::normal_distribution<float> gauss(0.0f, 0.02f);
  for (float& sample : noisy.samples()) sample = std::max(sample + gauss(random), 0.0f);
  const auto badPix = [&](bool correction) {
    auto depth = edof::estimateDepth(noisy, {}, {.noiseCorrection = correction});
    EXPECT_TRUE(depth) << depth.error().message;
    return depth ? scoreDisparity(depth->disparity, plain.disparity)->badPix : 100.0;
  };
  const double with = badPix(true), without = badPix(false);
  std::printf("flat noisy regions: BadPix(0.07) %.2f %% with the noise correction, %.2f %% without\n", with, without);
  EXPECT_LT(with, without - 5.0);
}

// Coarse texture (features four times the default's): with penalties scaled image-wide, a
// confident card's disparity runs over the faint evidence of the coarse background beside it; with
// penalties that follow the cost's contrast near each pixel (DepthOptions::contrastRadius, the
// default) the map must be better by a point. Measured: BadPix(0.07) 2.96 % against 5.05 % (13.09
// against 14.36 % before the view offsets were checked, DepthExperiment::offsetResidualCheck); the
// occlusion edges, since they follow slopes and count a 0.3 px step as a jump, mend part of the
// same halo (before: 13.03 against 15.45 %; when the penalties were chosen, 13.0 against 17.1 %,
// with features twice the default's 3.8 against 4.1 %, three times 4.3 against 5.3 %). The same
// scene is among the development scenes (bench/depth_scenes.hpp), so the means see it too.
TEST(DepthLayeredPlanes, PenaltiesFollowingLocalContrastKeepCoarseTextureApart) {
  const bench::DepthScene scene = bench::coarseLayeredPlanes(128);
  const auto badPix = [&](int contrastRadius) {
    auto depth = estimateDepth(scene.lightField, {.contrastRadius = contrastRadius});
    EXPECT_TRUE(depth) << depth.error().message;
    return depth ? scoreDisparity(depth->disparity, scene.disparity)->badPix : 100.0;
  };
  const double local = badPix(4), imageWide = badPix(0);
  std::printf("coarse texture: BadPix(0.07) %.2f %% with local penalties, %.2f %% image-wide\n", local, imageWide);
  EXPECT_LT(local, imageWide - 1.0);
}

// A second round of fine search and cleanup starts from the cleaned map, so a window's slices
// follow the planes where the first round's outliers had bent them, and searches at half the
// spacing: on the default planes both BadPix(0.07) and BadPix(0.03) must drop (measured 2.31
// against 2.72 % and 3.04 against 3.50 %).
TEST(DepthLayeredPlanes, SecondRefinementRoundGainsPrecision) {
  const LayeredPlanesLightField scene = renderLayeredPlanes(defaultLayeredPlanesScene(9, 128));
  // BadPix at 0.07 and at 0.03 px with `rounds` rounds.
  const auto badPix = [&](int rounds) {
    DepthOptions options;
    options.refineRounds = rounds;
    auto depth = estimateDepth(scene.lightField, options);
    EXPECT_TRUE(depth) << depth.error().message;
    if (!depth) return std::pair{100.0, 100.0};
    return std::pair{scoreDisparity(depth->disparity, scene.disparity)->badPix,
                     scoreDisparity(depth->disparity, scene.disparity, 0.03)->badPix};
  };
  const auto [one, oneFine] = badPix(1);
  const auto [two, twoFine] = badPix(2);
  std::printf(
      "layered planes, refinement rounds 1 and 2: BadPix(0.07) %.2f and %.2f %%, BadPix(0.03) %.2f and %.2f %%\n", one,
      two, oneFine, twoFine);
  EXPECT_LT(two, one - 0.2);
  EXPECT_LT(twoFine, oneFine - 0.2);
}

// A weakly textured plane (3 % contrast) before a strongly textured background: refocused far from
// the background's edge, the photograph shows it as a staircase of shifted copies, whose Laplacian
// spills onto the weak texture. With the defocus cue capped at twice the centre view's own
// (edof::DepthExperiment::defocusCeiling, the default) the weak plane must come out better
// (measured 3.42 against 4.18 %; 2.64 against 4.16 % with one round of refinement and cleanup;
// 2.87 against 6.84 % before the fine search started from a quadratic fit of the map, which mends
// part of the same error). Measured without the later rounds' cost check of the occlusion edges
// (DepthExperiment::reclaimCostCheck) and without the view offsets' correction for the map's error
// (offsetSlopeCorrection): with the check, 3.97 against 2.76 %; with both, 4.04 against 4.02 %.
// And without the centre row and column's gate (oneDimensionalGate): with it, 4.50 against 3.97 %,
// the ceiling no longer helping here (not looked into why).
// The development means with and without the ceiling: kDefocusCeiling's comment (cost_volume.cpp).
TEST(DepthLayeredPlanes, DefocusCeilingKeepsGhostEdgesOffWeakTexture) {
  LayeredPlanesScene scene;
  scene.ns = scene.nt = 96;
  TexturedPlane background, weak;
  background.disparity = -0.8;
  background.period = 4;
  weak.disparity = 0.6;
  weak.period = 8;
  weak.x0 = 0, weak.x1 = 96, weak.y0 = 48, weak.y1 = 96;
  scene.planes = {background, weak};
  const LayeredPlanesLightField rendered = renderLayeredPlanes(scene);
  // The weak plane's samples: those whose point, back in the centre view, falls in its extent.
  LightField lightField = rendered.lightField.copy();
  for (int v = 0; v < lightField.nv(); ++v)
    for (int u = 0; u < lightField.nu(); ++u)
      for (int c = 0; c < lightField.channels(); ++c)
        for (int t = 0; t < lightField.nt(); ++t)
          if (t + 0.5 + lightField.vFromCentre(v) * weak.disparity >= weak.y0 + 1)
            for (int s = 0; s < lightField.ns(); ++s) {
              float& sample = lightField.at(u, v, s, t, c);
              sample = 0.3f + 0.03f * (sample - 0.5f);
            }
  const auto badPix = [&](bool ceiling) {
    auto depth = edof::estimateDepth(lightField, {},
                                     {.defocusCeiling = ceiling,
                                      .oneDimensionalGate = false,
                                      .reclaimCostCheck = false,
                                      .offsetSlopeCorrection = false});
    EXPECT_TRUE(depth) << depth.error().message;
    return depth ? scoreDisparity(depth->disparity, rendered.disparity)->badPix : 100.0;
  };
  const double with = badPix(true), without = badPix(false);
  std::printf("weak texture beside strong: BadPix(0.07) %.2f %% with the defocus ceiling, %.2f %% without\n", with,
              without);
  EXPECT_LT(with, without - 0.5);
}

// The stages shown to DepthExperiment::observeStage (`depth_bench --stages`): in the order of
// depth.hpp, every round's, at every resolution and pass run; the full resolution's last is the
// map returned, and looking changes nothing.
TEST(DepthLayeredPlanes, StagesAreShownInOrderAndTheLastIsTheMap) {
  const LayeredPlanesLightField scene = renderLayeredPlanes(defaultLayeredPlanesScene(5, 48));
  std::vector<std::string> fullSize;
  std::vector<float> last;
  int smaller = 0;
  edof::DepthExperiment observed;
  observed.observeStage = [&](const std::string& stage, const Image& map) {
    if (map.width() < scene.disparity.width()) return void(++smaller);
    fullSize.push_back(stage);
    last.assign(map.pixels().begin(), map.pixels().end());
  };
  auto seen = edof::estimateDepth(scene.lightField, {}, observed);
  auto unseen = estimateDepth(scene.lightField);
  ASSERT_TRUE(seen && unseen);
  // Views that read as noisy are matched twice, the second time smoothed (DepthMap::prefilterSigma).
  std::vector<std::string> expected;
  for (int pass = 0; pass < (seen->prefilterSigma > 0 ? 2 : 1); ++pass)
    for (const char* stage : {"cost", "optimised", "refined 1", "filled 1", "reclaimed 1", "median 1", "refined 2",
                              "filled 2", "reclaimed 2", "median 2"})
      expected.push_back(stage);
  EXPECT_EQ(fullSize, expected);
  EXPECT_GT(smaller, 0);  // the view offsets' half-resolution passes
  const auto pixels = seen->disparity.pixels();
  EXPECT_TRUE(std::equal(pixels.begin(), pixels.end(), last.begin(), last.end()));
  const auto other = unseen->disparity.pixels();
  EXPECT_TRUE(std::equal(pixels.begin(), pixels.end(), other.begin(), other.end()));
}

// Views of a few pixels: the view offsets' half-resolution maps are 2 or 3 pixels across (views of
// 4-7), or skipped (2-3).
TEST(DepthLayeredPlanes, TinyViewsGiveAMap) {
  for (int size : {2, 3, 4, 5, 7}) {
    const LayeredPlanesLightField scene = renderLayeredPlanes(defaultLayeredPlanesScene(3, size));
    auto depth = estimateDepth(scene.lightField);
    ASSERT_TRUE(depth) << size << ": " << depth.error().message;
    for (float d : depth->disparity.pixels()) EXPECT_TRUE(std::isfinite(d)) << size;
  }
}

TEST(DepthLayeredPlanes, RefusesAnEmptyRange) {
  const LayeredPlanesLightField scene = renderLayeredPlanes(defaultLayeredPlanesScene(3, 16));
  EXPECT_FALSE(estimateDepth(scene.lightField, {.disparityMin = 1.0, .disparityMax = 1.0}));
  EXPECT_FALSE(estimateDepth(LightField()));
}

TEST(Distance, ThinLensThroughTheRefocusDepth) {
  const Optics optics = defaultLayeredPlanesScene().optics;  // f 90 mm, F 100 mm
  // Slope 0 is the plane in focus at capture: 1/z = 1/90 - 1/100.
  EXPECT_NEAR(*distanceFromDisparity(optics, 0.0), 900.0, 1e-6);
  // Positive disparity is nearer.
  EXPECT_LT(*distanceFromDisparity(optics, 1.0), 900.0);
  EXPECT_GT(*distanceFromDisparity(optics, -1.0), 900.0);
  // Focus beyond infinity.
  EXPECT_TRUE(std::isinf(*distanceFromDisparity(optics, -100.0)));
  Optics unknown = optics;
  unknown.focalLengthMm.reset();
  EXPECT_FALSE(distanceFromDisparity(unknown, 0.0));
}

TEST(ColorMap, TurboRunsFromBlueToRed) {
  float low[3], high[3], middle[3];
  turbo(0.1, low), turbo(0.95, high), turbo(0.5, middle);
  EXPECT_GT(low[2], low[0]);     // blue end
  EXPECT_GT(high[0], high[2]);   // red end
  EXPECT_GT(middle[1], low[1]);  // bright green-yellow middle
  Image ramp(4, 1, 1);
  for (int x = 0; x < 4; ++x) ramp.at(x, 0, 0) = float(x);
  ramp.at(3, 0, 0) = std::numeric_limits<float>::infinity();
  const Image picture = colorMap(ramp);
  EXPECT_EQ(picture.channels(), 3);
  EXPECT_EQ(picture.at(3, 0, 0), 0.0f);  // non-finite: black
  float start[3], end[3];
  turbo(0.0, start), turbo(1.0, end);
  EXPECT_NEAR(picture.at(0, 0, 2), start[2], 1e-6);  // the finite range [0, 2] spans the map
  EXPECT_NEAR(picture.at(2, 0, 0), end[0], 1e-6);
}

}  // namespace
}  // namespace lfcam
