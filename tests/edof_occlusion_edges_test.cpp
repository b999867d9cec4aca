// Occlusion edges (src/edof/occlusion_edges.cpp): the distance to jumps against a brute-force
// reference, the fattened background beside a nearer square given back, and the effect on the
// layered-planes scene through estimateDepth (DepthOptions::occlusionBand).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "depth_scenes.hpp"
#include "edof/depth_experiment.hpp"
#include "edof/edof_internal.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/edof/disparity_scores.hpp"
#include "lfcam/synth/layered_planes.hpp"

namespace lfcam::edof {
namespace {

// Reference: the chessboard distance to the nearest pixel of any jump pair, found by search.
std::vector<int> jumpDistanceReference(const std::vector<float>& map, int width, int height, float jump, int cap) {
  std::vector<char> onJump(map.size(), 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int p = y * width + x;
      for (const int q : {x + 1 < width ? p + 1 : -1, y + 1 < height ? p + width : -1})
        if (q >= 0 && std::abs(map[q] - map[p]) > jump) onJump[p] = onJump[q] = 1;
    }
  std::vector<int> distance(map.size(), cap + 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int yy = 0; yy < height; ++yy)
        for (int xx = 0; xx < width; ++xx)
          if (onJump[yy * width + xx])
            distance[y * width + x] = std::min(distance[y * width + x], std::max(std::abs(xx - x), std::abs(yy - y)));
  return distance;
}

TEST(OcclusionEdges, JumpDistanceAgreesWithTheReference) {
  std::mt19937 random(66);
  std::uniform_int_distribution<int> size(1, 24), level(0, 3), coin(0, 9);
  for (int trial = 0; trial < 300; ++trial) {
    const int width = size(random), height = size(random), cap = 1 + trial % 6;
    // Piecewise-constant maps with a few jumps (levels 0.4 apart: only two-level steps count).
    std::vector<float> map(std::size_t(width) * height);
    float current = 0;
    for (float& v : map) {
      if (coin(random) == 0) current = 0.4f * float(level(random));
      v = current;
    }
    const std::vector<int> expected = jumpDistanceReference(map, width, height, 0.5f, cap);
    ASSERT_EQ(jumpDistance(map.data(), width, height, 0.5f, cap), expected)
        << "trial " << trial << ", " << width << "x" << height << ", cap " << cap;
  }
}

// A nearer square (disparity 1) of its own colour on a plain far background (-1); the map gives
// the square's disparity 2 px too far all round, as the optimisation does where the background
// has no texture.
TEST(OcclusionEdges, FattenedBackgroundReturnsToTheBackground) {
  const int size = 64, x0 = 20, x1 = 44;
  Image guide(size, size, 3);
  std::vector<float> map(std::size_t(size) * size);
  auto inside = [](int x, int y, int lo, int hi) { return x >= lo && x < hi && y >= lo && y < hi; };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool square = inside(x, y, x0, x1);
      const float colour[3] = {square ? 0.9f : 0.3f, square ? 0.85f : 0.35f, square ? 0.8f : 0.3f};
      for (int c = 0; c < 3; ++c) guide.at(x, y, c) = colour[c];
      map[std::size_t(y) * size + x] = inside(x, y, x0 - 2, x1 + 2) ? 1.0f : -1.0f;
    }
  reclaimOcclusionEdges(guide, 3, true, map.data());
  int wrong = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) wrong += map[std::size_t(y) * size + x] != (inside(x, y, x0, x1) ? 1.0f : -1.0f);
  EXPECT_EQ(wrong, 0);

  // The other way round (the background over the square's edge) is left alone: pixels only move
  // to a farther surface.
  std::vector<float> eroded(map.size());
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) eroded[std::size_t(y) * size + x] = inside(x, y, x0 + 2, x1 - 2) ? 1.0f : -1.0f;
  std::vector<float> same = eroded;
  reclaimOcclusionEdges(guide, 3, true, same.data());
  EXPECT_EQ(same, eroded);
  // Band 0: off.
  std::vector<float> fattened(map.size());
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) fattened[std::size_t(y) * size + x] = inside(x, y, x0 - 2, x1 + 2) ? 1.0f : -1.0f;
  same = fattened;
  reclaimOcclusionEdges(guide, 0, true, same.data());
  EXPECT_EQ(same, fattened);
}

// The same on a slanted background (a floor behind a statue: 0.03 px per pixel across): the
// pixels given back take the background's disparity where they are, its voters carried along its
// slope; without the slope they take the voters' median, which lies a few pixels outwards.
TEST(OcclusionEdges, FattenedBackgroundFollowsItsSlope) {
  const int size = 64, x0 = 20, x1 = 44;
  Image guide(size, size, 3);
  std::vector<float> map(std::size_t(size) * size);
  auto inside = [](int x, int y, int lo, int hi) { return x >= lo && x < hi && y >= lo && y < hi; };
  auto background = [](int x) { return -1.0f + 0.03f * float(x); };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool square = inside(x, y, x0, x1);
      for (int c = 0; c < 3; ++c) guide.at(x, y, c) = square ? 0.9f : 0.3f;
      map[std::size_t(y) * size + x] = inside(x, y, x0 - 2, x1 + 2) ? 2.0f : background(x);
    }
  std::vector<float> flat = map;
  reclaimOcclusionEdges(guide, 3, true, map.data());
  reclaimOcclusionEdges(guide, 3, false, flat.data());
  float worst = 0, worstFlat = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::size_t p = std::size_t(y) * size + x;
      const float truth = inside(x, y, x0, x1) ? 2.0f : background(x);
      worst = std::max(worst, std::abs(map[p] - truth));
      worstFlat = std::max(worstFlat, std::abs(flat[p] - truth));
    }
  EXPECT_LT(worst, 1e-3f);
  EXPECT_GT(worstFlat, 0.07f);
}

// A bar 2 px wide (disparity 1) of another colour than the background (-1): every one of its
// pixels lies within the band of a jump, so none votes for it; the background's voters, of
// another colour, must not take it over by their faint likeness (without the floor of one full
// vote they did).
TEST(OcclusionEdges, ThinBarOfItsOwnColourKeepsItsDisparity) {
  const int size = 48, x0 = 23, x1 = 25;
  Image guide(size, size, 3);
  std::vector<float> map(std::size_t(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool bar = x >= x0 && x < x1;
      const float colour[3] = {bar ? 0.8f : 0.35f, bar ? 0.3f : 0.45f, bar ? 0.2f : 0.5f};
      for (int c = 0; c < 3; ++c) guide.at(x, y, c) = colour[c];
      map[std::size_t(y) * size + x] = bar ? 1.0f : -1.0f;
    }
  const std::vector<float> before = map;
  reclaimOcclusionEdges(guide, 3, true, map.data());
  EXPECT_EQ(map, before);
  // A bar of the background's colour is taken back: it is the fattening the step is for.
  for (int y = 0; y < size; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) guide.at(x, y, c) = guide.at(0, y, c);
  reclaimOcclusionEdges(guide, 3, true, map.data());
  for (float v : map) ASSERT_EQ(v, -1.0f);
}

// A strip 5 px wide (disparity 1) of the background's colour: every pixel lies within the band,
// so the background's voters take it, unless the cost check vetoes the move; the check is asked
// with the pixel's own disparity, the farther one, and no voter of the strip's own (it is narrower
// than the band). A strip 11 px wide has such voters, in its middle beyond the band.
TEST(OcclusionEdges, CostCheckMayVetoAMove) {
  const int size = 48, x0 = 21, x1 = 26;
  Image guide(size, size, 3);
  std::vector<float> map(std::size_t(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      for (int c = 0; c < 3; ++c) guide.at(x, y, c) = 0.4f;
      map[std::size_t(y) * size + x] = x >= x0 && x < x1 ? 1.0f : -1.0f;
    }
  const std::vector<float> before = map;
  std::vector<float> vetoed = map;
  std::atomic<int> asked = 0, misplaced = 0;  // asked from several threads
  reclaimOcclusionEdges(guide, 3, true, vetoed.data(), [&](std::size_t p, float from, float to, int ownVoters) {
    const int x = int(p % size);
    misplaced += !(x >= x0 && x < x1 && from == 1.0f && to == -1.0f && ownVoters == 0);
    ++asked;
    return x == x0;  // only the strip's first column may move
  });
  EXPECT_EQ(misplaced, 0);
  EXPECT_EQ(asked, (x1 - x0) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      ASSERT_EQ(vetoed[std::size_t(y) * size + x], x > x0 && x < x1 ? 1.0f : -1.0f) << x << ", " << y;
  reclaimOcclusionEdges(guide, 3, true, map.data());
  for (float v : map) ASSERT_EQ(v, -1.0f);
  EXPECT_NE(map, before);
  std::vector<float> wide(std::size_t(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) wide[std::size_t(y) * size + x] = x >= 16 && x < 27 ? 1.0f : -1.0f;
  std::atomic<int> askedWide = 0, withoutVoters = 0;
  reclaimOcclusionEdges(guide, 3, true, wide.data(), [&](std::size_t, float, float, int ownVoters) {
    ++askedWide;
    withoutVoters += ownVoters == 0;
    return false;
  });
  EXPECT_GT(askedWide, 0);
  EXPECT_EQ(withoutVoters, 0);
}

// On the layered planes (textured cards over a cloudy background), through estimateDepth: fewer
// bad pixels overall and on the background beside nearer cards (within 3 px of a pixel nearer by
// more than 0.2 in the truth).
TEST(OcclusionEdges, LayeredPlanesLoseTheirFattenedBorders) {
  const LayeredPlanesLightField scene = renderLayeredPlanes(defaultLayeredPlanesScene(9, 128));
  const Image& truth = scene.disparity;
  const int w = truth.width(), h = truth.height();
  double badPix[2] = {}, besideBad[2] = {};
  for (int band : {0, 3}) {
    auto depth = estimateDepth(scene.lightField, {.occlusionBand = band});
    ASSERT_TRUE(depth) << depth.error().message;
    auto scores = scoreDisparity(depth->disparity, truth);
    ASSERT_TRUE(scores);
    badPix[band > 0] = scores->badPix;
    long beside = 0, bad = 0;
    for (int y = 15; y < h - 15; ++y)
      for (int x = 15; x < w - 15; ++x) {
        bool nearer = false;
        for (int dy = -3; dy <= 3; ++dy)
          for (int dx = -3; dx <= 3; ++dx) nearer = nearer || truth.at(x + dx, y + dy, 0) > truth.at(x, y, 0) + 0.2f;
        if (!nearer) continue;
        ++beside;
        bad += std::abs(depth->disparity.at(x, y, 0) - truth.at(x, y, 0)) > 0.07f;
      }
    besideBad[band > 0] = 100.0 * double(bad) / double(std::max(beside, 1L));
  }
  std::printf(
      "layered planes: BadPix(0.07) %.2f %% with occlusionBand 3, %.2f %% without; background within 3 px "
      "of a nearer card %.1f %% bad with, %.1f %% without\n",
      badPix[1], badPix[0], besideBad[1], besideBad[0]);
  EXPECT_LT(badPix[1], badPix[0] - 1.0);
  EXPECT_LT(besideBad[1], besideBad[0] - 10.0);
}

// Narrow near parts (fingers before a far wall, bench/depth_scenes.hpp) through estimateDepth: the
// reclaim, vetoed where the cost volume disagrees (in the first round on parts narrower than the
// band, in the later ones everywhere), eats less of them.
TEST(OcclusionEdges, CostCheckKeepsNarrowNearParts) {
  const bench::DepthScene scene = bench::narrowNearParts(128);
  const DepthOptions options{.disparityMin = scene.disparityMin, .disparityMax = scene.disparityMax};
  double badPix[2] = {}, mse[2] = {};
  for (bool check : {false, true}) {
    DepthExperiment experiment;
    experiment.reclaimCostCheck = check;
    auto depth = estimateDepth(scene.lightField, options, experiment);
    ASSERT_TRUE(depth) << depth.error().message;
    auto scores = scoreHci(depth->disparity, scene.disparity);
    ASSERT_TRUE(scores) << scores.error().message;
    badPix[check] = scores->badPix007;
    mse[check] = scores->mse100;
  }
  std::printf("narrow near parts: BadPix(0.07) %.2f %% with the cost check, %.2f %% without; MSE x100 %.1f, %.1f\n",
              badPix[1], badPix[0], mse[1], mse[0]);
  EXPECT_LT(badPix[1], badPix[0] - 1.0);
}

}  // namespace
}  // namespace lfcam::edof
