// Depth on views whose brightness changes across the aperture (a sheen): the view offsets that
// removeViewOffsets (src/edof/depth.cpp) measures and takes out before matching.
#include <gtest/gtest.h>

#include <cstdio>

#include "depth_scenes.hpp"
#include "edof/depth_experiment.hpp"
#include "lfcam/depth.hpp"
#include "lfcam/disparity_scores.hpp"

namespace lfcam::edof {
namespace {

// The glossy card of weak texture (bench/depth_scenes.hpp) at 256 px per view, where its sheen,
// -10 % to +10 % across the aperture, pulls the card's disparity: the offsets measured after the
// part of each view's difference that the first map's error explains is taken out leave less of
// that pull than the offsets measured with it (3.65 % against 7.08 % when written).
TEST(DepthViewOffsets, MeasuredWithoutTheMapsErrorLeaveLessOfASheen) {
  const bench::DepthScene scene = bench::weakTextureGlossy(256);
  const DepthOptions options{.disparityMin = scene.disparityMin, .disparityMax = scene.disparityMax};
  double badPix[2] = {};
  for (bool corrected : {false, true}) {
    DepthExperiment experiment;
    experiment.offsetSlopeCorrection = corrected;
    auto depth = estimateDepth(scene.lightField, options, experiment);
    ASSERT_TRUE(depth) << depth.error().message;
    auto scores = scoreHci(depth->disparity, scene.disparity);
    ASSERT_TRUE(scores) << scores.error().message;
    badPix[corrected] = scores->badPix007;
  }
  std::printf("glossy weak card at 256 px: BadPix(0.07) %.2f %% with the map's error taken out, %.2f %% without\n",
              badPix[1], badPix[0]);
  EXPECT_LT(badPix[1], badPix[0] - 2.0);
}

}  // namespace
}  // namespace lfcam::edof
