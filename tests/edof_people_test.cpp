// Figure 15 on the simulator's `people` scene (scene.hpp): cards at four depths seen by a small
// plenoptic camera (9x9 views of 80x80), the ideal light field with sensor-like noise added. In
// the visible interior of every card, the all-in-focus composite is as sharp as the best-focused
// photograph of its focal stack (within 5%) and at least 3x less noisy than the central
// sub-aperture image, which has the same depth of field. Both ways of choosing slices are checked:
// the focus measure (`lfcam edof`) and a depth map estimated from the same noisy light field
// (`lfcam depth` then `lfcam edof --depth`). And `lfcam denoise` on the same light fields: the
// centre view less noisy and as sharp on every card.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "edof/depth_experiment.hpp"
#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/edof/disparity_scores.hpp"
#include "lfcam/render/denoise.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "people_camera.hpp"
#include "people_cards.hpp"

namespace lfcam {
namespace {

using test::Card;

// Variance of the 4-neighbour Laplacian of the channel mean over `pixels` (not on the border).
double laplacianVariance(const Image& image, const std::vector<std::size_t>& pixels) {
  const int w = image.width();
  auto mean = [&](std::size_t i) {
    double sum = 0;
    for (int c = 0; c < image.channels(); ++c) sum += image.plane(c)[i];
    return sum / image.channels();
  };
  double sum = 0, squares = 0;
  for (std::size_t i : pixels) {
    const double lap = mean(i - 1) + mean(i + 1) + mean(i - w) + mean(i + w) - 4 * mean(i);
    sum += lap, squares += lap * lap;
  }
  const double m = sum / double(pixels.size());
  return squares / double(pixels.size()) - m * m;
}

double rmsDifference(const Image& a, const Image& b, const std::vector<std::size_t>& pixels) {
  double sum = 0;
  for (int c = 0; c < a.channels(); ++c)
    for (std::size_t i : pixels) {
      const double d = a.plane(c)[i] - b.plane(c)[i];
      sum += d * d;
    }
  return std::sqrt(sum / double(pixels.size() * a.channels()));
}

class PeopleAllInFocus : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const CameraModel camera = test::peopleCamera();
    const Scene scene = *builtinScene("people", camera);
    auto ideal = idealLightField(scene, camera);
    ASSERT_TRUE(ideal) << ideal.error().message;
    auto depth = idealDepth(scene, camera);
    ASSERT_TRUE(depth) << depth.error().message;
    clean_ = new LightField(std::move(*ideal));
    noisy_ = new LightField(clean_->copy());
    noisy_->metadata = clean_->metadata;
    // Shot and read noise per sample, sigma^2 = 0.02^2 + 0.002 x value (about 2-4% of the signal).
    std::mt19937 generator(11);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    for (float& sample : noisy_->samples())
      sample += std::sqrt(0.0004f + 0.002f * std::max(sample, 0.0f)) * normal(generator);

    // The exact disparity of every pixel (non-finite where the optics give none), and the cards'
    // disparities and the pixels well inside each card.
    const Optics& optics = *clean_->metadata.optics;
    const int w = depth->width(), h = depth->height();
    truth_ = new Image(w, h, 1);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        truth_->at(x, y, 0) = float(disparityFromDistance(optics, depth->at(x, y, 0)).value_or(NAN));
    cards_ = new std::vector<Card>(test::sceneCards(scene, *depth, optics));
  }
  static void TearDownTestSuite() {
    delete clean_;
    delete noisy_;
    delete cards_;
    delete truth_;
  }

  // Figure 15's two claims, card by card. The composite's slices were chosen on the noisy light
  // field; the same choice applied to the noise-free one separates what the montage does to
  // sharpness (compared with the noise-free slices, so that noise does not count as detail) from
  // what it does to noise (noisy composite minus noise-free composite).
  static void expectSharpAndQuiet(const AllInFocus& result) {
    AllInFocusOptions same = stackOptions();
    same.disparity = &result.slope;
    auto cleanResult = allInFocus(*clean_, same);
    ASSERT_TRUE(cleanResult) << cleanResult.error().message;
    ASSERT_EQ(cleanResult->slopes, result.slopes);
    const Image& cleanComposite = cleanResult->photo;
    const int u = (noisy_->nu() - 1) / 2, v = (noisy_->nv() - 1) / 2;
    const Image centreNoisy = noisy_->subApertureImage(u, v), centreClean = clean_->subApertureImage(u, v);
    std::vector<Image> stack;
    for (double slope : result.slopes) stack.push_back(refocus(*clean_, slope));
    for (const Card& card : *cards_) {
      SCOPED_TRACE(card.name);
      ASSERT_GE(card.interior.size(), 100u) << "too little of the card is visible to measure";
      double best = 0;
      for (const Image& slice : stack) best = std::max(best, laplacianVariance(slice, card.interior));
      const double composite = laplacianVariance(cleanComposite, card.interior);
      const double compositeNoise = rmsDifference(result.photo, cleanComposite, card.interior);
      const double centreNoise = rmsDifference(centreNoisy, centreClean, card.interior);
      std::printf(
          "%-15s (disparity %+.2f, %4zu px): sharpness %.4g of best slice %.4g (%.1f%%); noise %.4f vs "
          "centre view %.4f (%.1fx)\n",
          card.name.c_str(), card.disparity, card.interior.size(), composite, best, 100 * composite / best,
          compositeNoise, centreNoise, centreNoise / compositeNoise);
      EXPECT_GE(composite, 0.95 * best);
      EXPECT_GE(centreNoise, 3 * compositeNoise);
    }
  }

  static AllInFocusOptions stackOptions() {
    AllInFocusOptions options;
    double low = 1e9, high = -1e9;
    for (const Card& card : *cards_) low = std::min(low, card.disparity), high = std::max(high, card.disparity);
    options.disparityMin = low - 0.25;
    options.disparityMax = high + 0.25;
    return options;
  }

  static LightField* clean_;
  static LightField* noisy_;
  static std::vector<Card>* cards_;
  static Image* truth_;
};
LightField* PeopleAllInFocus::clean_ = nullptr;
LightField* PeopleAllInFocus::noisy_ = nullptr;
std::vector<Card>* PeopleAllInFocus::cards_ = nullptr;
Image* PeopleAllInFocus::truth_ = nullptr;

TEST_F(PeopleAllInFocus, FocusMeasureCompositeIsSharpAndQuiet) {
  auto result = allInFocus(*noisy_, stackOptions());
  ASSERT_TRUE(result) << result.error().message;
  expectSharpAndQuiet(*result);
}

TEST_F(PeopleAllInFocus, EstimatedDepthCompositeIsSharpAndQuiet) {
  const AllInFocusOptions base = stackOptions();
  auto depth = estimateDepth(*noisy_, {.disparityMin = base.disparityMin, .disparityMax = base.disparityMax});
  ASSERT_TRUE(depth) << depth.error().message;
  AllInFocusOptions options = base;
  options.disparity = &depth->disparity;
  auto result = allInFocus(*noisy_, options);
  ASSERT_TRUE(result) << result.error().message;
  expectSharpAndQuiet(*result);
}

// The hyperfan of the cards' disparity range (0.25 wider each side) on the noisy light field. On
// every card the noise of the centre view (by linearity: filtered noisy minus filtered noise-free)
// falls by more than 2x (measured 2.02-2.12x with the default bandwidth), and the noise-free
// centre view filtered the same way keeps at least 85 % of the sharpness of the photograph
// refocused on the card (Laplacian variance; measured: 95 % on the card in focus, 1.6-4.0x on the
// others). It keeps 81-107 % of the centre view's own: what the views do not share (aliasing of
// textures finer than the microlenses) is no surface in the passband (bench/denoise_bench.cpp
// measures the sharpness that is, on sine gratings, on sensor captures).
TEST_F(PeopleAllInFocus, DenoiseLowersTheCentreViewsNoiseAndKeepsWhatTheViewsShare) {
  const AllInFocusOptions range = stackOptions();
  const DenoiseOptions options{.slopeMin = *range.disparityMin, .slopeMax = *range.disparityMax};
  auto noisyFiltered = denoise(*noisy_, options);
  auto cleanFiltered = denoise(*clean_, options);
  ASSERT_TRUE(noisyFiltered && cleanFiltered);
  const int u = (noisy_->nu() - 1) / 2, v = (noisy_->nv() - 1) / 2;
  const Image centreClean = clean_->subApertureImage(u, v), centreNoisy = noisy_->subApertureImage(u, v);
  const Image after = noisyFiltered->subApertureImage(u, v), cleanAfter = cleanFiltered->subApertureImage(u, v);
  for (const Card& card : *cards_) {
    SCOPED_TRACE(card.name);
    const double noiseBefore = rmsDifference(centreNoisy, centreClean, card.interior);
    const double noiseAfter = rmsDifference(after, cleanAfter, card.interior);
    const double sharpness = laplacianVariance(cleanAfter, card.interior);
    const double refocused = laplacianVariance(refocus(*clean_, card.disparity), card.interior);
    const double centre = laplacianVariance(centreClean, card.interior);
    std::printf(
        "%-15s (disparity %+.2f): centre view noise %.4f -> %.4f (%.2fx); sharpness %.1f%% of the centre view's, "
        "the refocused photo's %.1f%%\n",
        card.name.c_str(), card.disparity, noiseBefore, noiseAfter, noiseBefore / noiseAfter, 100 * sharpness / centre,
        100 * refocused / centre);
    EXPECT_GT(noiseBefore / noiseAfter, 2.0);
    EXPECT_GT(sharpness, 0.85 * refocused);
  }
}

// Issue 6 asks for the depth scores of every scene that can be run, the simulator's with exact
// depth included: scored as the HCI benchmark scores (its 15 px border left out: 50 x 50 pixels
// here), on the noise-free and the noisy light field. Measured: BadPix(0.07) 1.92 % and 2.21 %,
// MSE x100 0.64 and 0.60 with today's defaults; 4.8 % and 4.5 %, 0.78 and 0.82 with the first
// defaults chosen on the development scenes (issue 18); 5.2 % and
// 4.4 %, 0.95 and 0.81 with issue 6's (6.8 % and 5.0 %, 0.96 and 0.85 before issue 6's sixth round's
// defaults; 10.2 % and 7.8 % before DepthOptions::occlusionBand and the fine
// search's radius 2; 11.0 % and 8.6 % before edof::DepthExperiment::aggregateSubsetsApart; 17.9 %
// and 16.6 % before edof::DepthExperiment::refineAggregateHalves; 47.2 % and 36.0 % with
// edof::DepthExperiment::lockingCorrection = 1 before it, which is why that is off).
TEST_F(PeopleAllInFocus, DepthScoresAgainstTheExactDisparity) {
  const AllInFocusOptions range = stackOptions();
  for (const LightField* lightField : {clean_, noisy_}) {
    auto depth = estimateDepth(*lightField, {.disparityMin = range.disparityMin, .disparityMax = range.disparityMax});
    ASSERT_TRUE(depth) << depth.error().message;
    auto strict = scoreDisparity(depth->disparity, *truth_, 0.07);
    auto loose = scoreDisparity(depth->disparity, *truth_, 0.03);
    ASSERT_TRUE(strict && loose);
    const char* which = lightField == clean_ ? "noise-free" : "noisy";
    std::printf("people, %s: BadPix(0.07) %.2f %%, BadPix(0.03) %.2f %%, MSE x100 %.3f (%ld px)\n", which,
                strict->badPix, loose->badPix, strict->mse100, strict->pixels);
    EXPECT_LT(strict->badPix, 9.0) << which;
    EXPECT_LT(strict->mse100, 2.5) << which;
  }
}

// The automatic prefilter (DepthOptions::prefilterSigma -1): views that disagree at their best
// match are smoothed before matching, which helps, whether they disagree through noise or through
// aliasing (the fixture's views sample each microlens at one point); views that agree (the
// layered planes, rendered with area sampling) are matched as they are. Measured: point-sampled
// 2.25 % BadPix(0.07) with it, 2.50 % without; noisy 2.58 against 2.75 % (before the cleanup
// followed slopes and took a 0.3 px step as an occlusion: 1.92 against 2.21 % and 2.21 against
// 2.71 %). On the development scenes it brings 2.33 -> 1.81 % (mean BadPix(0.07), `depth_bench
// --development-only --options` with prefilter-sigma 0 against the defaults).
TEST_F(PeopleAllInFocus, AutomaticPrefilterSmoothsOnlyViewsThatDisagree) {
  const AllInFocusOptions range = stackOptions();
  for (const LightField* lightField : {clean_, noisy_}) {
    double badPix[2] = {};
    for (int automatic : {0, 1}) {
      auto depth = estimateDepth(*lightField, {.disparityMin = range.disparityMin,
                                               .disparityMax = range.disparityMax,
                                               .prefilterSigma = automatic ? -1.0 : 0.0});
      ASSERT_TRUE(depth) << depth.error().message;
      auto scores = scoreDisparity(depth->disparity, *truth_, 0.07);
      ASSERT_TRUE(scores);
      badPix[automatic] = scores->badPix;
    }
    const char* which = lightField == noisy_ ? "noisy" : "point-sampled";
    std::printf("people, %s: BadPix(0.07) %.2f %% with the automatic prefilter, %.2f %% without\n", which, badPix[1],
                badPix[0]);
    EXPECT_LT(badPix[1], badPix[0] - 0.1) << which;
  }
  const LayeredPlanesLightField planes = renderLayeredPlanes(defaultLayeredPlanesScene(9, 96));
  auto automatic = estimateDepth(planes.lightField, {.prefilterSigma = -1});
  auto none = estimateDepth(planes.lightField, {.prefilterSigma = 0});
  ASSERT_TRUE(automatic && none);
  EXPECT_TRUE(std::equal(automatic->disparity.pixels().begin(), automatic->disparity.pixels().end(),
                         none->disparity.pixels().begin(), none->disparity.pixels().end()));
}

// The fine search's subsets of views aggregated apart, then the best (edof::DepthExperiment::
// refineAggregateHalves), against the best per pixel before aggregating. Measured on the noisy
// light field: BadPix(0.07) 8.6 % against 10.8 % (16.6 % before, with the fine search's radius 8),
// both with the cost volume's subsets taken per pixel (aggregateSubsetsApart off); now (fine-search
// radius 2, occlusionBand 3, the sixth round's defaults) 4.1 % against 7.4 %; 4.7 % against 6.5 %
// with the defaults chosen on the development scenes (issue 18). Measured on the views as they
// are, 2.8 % against 4.0 %: the automatic prefilter of noisy views leaves the subsets less to mend
// (2.25 % against 2.50 %).
TEST_F(PeopleAllInFocus, FineSearchAggregatesSubsetsApart) {
  const AllInFocusOptions range = stackOptions();
  double badPix[2] = {};
  for (bool apart : {false, true}) {
    auto depth = edof::estimateDepth(
        *noisy_, {.disparityMin = range.disparityMin, .disparityMax = range.disparityMax, .prefilterSigma = 0},
        {.aggregateSubsetsApart = false, .refineAggregateHalves = apart});
    ASSERT_TRUE(depth) << depth.error().message;
    auto scores = scoreDisparity(depth->disparity, *truth_, 0.07);
    ASSERT_TRUE(scores);
    badPix[apart] = scores->badPix;
  }
  std::printf("people, noisy: BadPix(0.07) %.2f %% with the subsets aggregated apart, %.2f %% without\n", badPix[1],
              badPix[0]);
  EXPECT_LT(badPix[1], badPix[0] - 1.0);
}

// The same in the cost volume (edof::DepthExperiment::aggregateSubsetsApart): each subset's slices
// aggregated by the first guided filter, then the lowest subset per label. Measured: BadPix(0.07)
// noise-free 10.2 % against 11.0 %, noisy 7.8 % against 8.6 % (fine-search radius 4, no
// occlusionBand); the sum of both 9.6 % against 11.5 % with issue 6's defaults, 9.3 % against
// 9.4 % with the defaults chosen on the development scenes (issue 18: the fine search's smaller
// window and the lighter fill recover most of what it brought), 4.08 % both with the views'
// offsets removed, 4.12 % against 4.08 % with the noise correction, 4.04 % both with the local
// penalties, 4.83 % against 4.71 % once the cleanup followed slopes. On the development scenes it
// still brings 1.87 -> 1.81 % (mean BadPix(0.07), `depth_bench --development-only
// --subsets-together` against the defaults; 2.77 -> 2.36 % when it was chosen), so here it must not
// cost more than a fifth of a point.
TEST_F(PeopleAllInFocus, CostVolumeAggregatesSubsetsApart) {
  const AllInFocusOptions range = stackOptions();
  double total[2] = {};
  for (bool apart : {false, true})
    for (const LightField* lightField : {clean_, noisy_}) {
      auto depth =
          edof::estimateDepth(*lightField, {.disparityMin = range.disparityMin, .disparityMax = range.disparityMax},
                              {.aggregateSubsetsApart = apart});
      ASSERT_TRUE(depth) << depth.error().message;
      auto scores = scoreDisparity(depth->disparity, *truth_, 0.07);
      ASSERT_TRUE(scores);
      total[apart] += scores->badPix;
    }
  std::printf(
      "people, noise-free + noisy: BadPix(0.07) %.2f %% with the cost volume's subsets aggregated apart, "
      "%.2f %% without\n",
      total[1], total[0]);
  EXPECT_LE(total[1], total[0] + 0.2);
}

// The two experiments of matching a view-dependent brightness away (DepthExperiment, measured by
// depth_bench --high-pass and --gradient): each changes the map, and keeps it a depth map of the
// scene (BadPix(0.07) of the noise-free light field under 15 %, against about 2 % by default).
TEST_F(PeopleAllInFocus, OffsetInvariantCostExperimentsStillFindTheCards) {
  const AllInFocusOptions range = stackOptions();
  const DepthOptions options{.disparityMin = range.disparityMin, .disparityMax = range.disparityMax};
  auto plain = edof::estimateDepth(*clean_, options, {});
  ASSERT_TRUE(plain) << plain.error().message;
  for (const edof::DepthExperiment& experiment :
       {edof::DepthExperiment{.highPassRadius = 2}, edof::DepthExperiment{.gradientWeight = 0.5}}) {
    auto depth = edof::estimateDepth(*clean_, options, experiment);
    ASSERT_TRUE(depth) << depth.error().message;
    auto scores = scoreDisparity(depth->disparity, *truth_, 0.07);
    ASSERT_TRUE(scores);
    std::printf("people, noise-free: BadPix(0.07) %.2f %% (high-pass %d, gradient weight %.1f)\n", scores->badPix,
                experiment.highPassRadius, experiment.gradientWeight);
    EXPECT_LT(scores->badPix, 15.0);
    EXPECT_FALSE(std::equal(depth->disparity.pixels().begin(), depth->disparity.pixels().end(),
                            plain->disparity.pixels().begin(), plain->disparity.pixels().end()));
  }
}

}  // namespace
}  // namespace lfcam
