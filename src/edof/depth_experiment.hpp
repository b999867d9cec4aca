// Switches of the depth estimator kept to measure what a step brings (tests/edof_people_test.cpp,
// tests/depth_layered_planes_test.cpp, bench/depth_bench.cpp), not settings for users: the
// defaults are what estimateDepth does.
#pragma once

#include <functional>
#include <string>

#include "lfcam/edof/depth.hpp"

namespace lfcam::edof {

struct DepthExperiment {
  bool aggregateSubsetsApart = true;  // cost volume: aggregate each subset's cost, then the best
  bool refineAggregateHalves = true;  // fine search: the same
  // Scale of the interpolation-bias term removed from the cost; 0: none. It took antinous from
  // 14.2 to 13.3 % BadPix(0.07) but the simulator's people scene from 17.9 to 47.2 %.
  double lockingCorrection = 0.0;
  // Views less their local mean (a box of this radius) before matching, so that a brightness that
  // changes across the aperture (a sheen) or between views (vignetting left over) cancels; 0: none.
  // Held-out antinous 7.16 -> 3.53 % BadPix(0.07) at radius 2, but people 3.17 -> 8.58 % (the mean
  // mixes the two sides of every occlusion edge): `depth_bench --high-pass R`.
  int highPassRadius = 0;
  // Weight a of the gradient in the matching cost, (1 - a) dI^2 + a |d grad I|^2 over the views'
  // sRGB luminance (Hosni et al. 2013's cost): a brightness offset between views cancels in the
  // gradient, within a pixel of occlusion edges; 0: none. Antinous 7.16 -> 5.79 % at 0.5, 4.96 %
  // at 0.8, but the development mean 2.50 -> 2.62 % and 2.98 % (noisy people 5.17 % at 0.8), the
  // automatic prefilter's threshold not scaled for it: `depth_bench --gradient A`.
  double gradientWeight = 0;
  // The noise variance that bilinear sampling removes added back to the cost of noisy views
  // (depth.cpp, ViewNoise); off: `depth_bench --no-noise-correction`.
  bool noiseCorrection = true;
  // The defocus cue capped at kDefocusCeiling times the centre view's own (cost_volume.cpp); off:
  // `depth_bench --no-defocus-ceiling`.
  bool defocusCeiling = true;
  // The centre row and column join the lowest subset only where their cost has contrast or matches
  // better than noise explains (cost_volume.cpp, joinOneDimensional); off: `depth_bench --no-one-dimensional-gate`.
  bool oneDimensionalGate = true;
  // The weighted median and the occlusion edges carry disparities along the map's slope
  // (guidedWeightedMedian, reclaimOcclusionEdges); off: `depth_bench --flat-cleanup`.
  bool slantedCleanup = true;
  // The occlusion edges' reclaim in every round of refinement and cleanup, not the first only;
  // the first only: `depth_bench --reclaim-first-round-only` (design.md, "Depth").
  bool reclaimEveryRound = true;
  // A reclaim move only where the cost volume agrees (depth.cpp, kReclaimCostMargin): after the
  // first round everywhere, in it on parts narrower than the band; without any:
  // `depth_bench --no-reclaim-cost-check`; without the first round's: `--no-first-round-cost-check`.
  bool reclaimCostCheck = true;
  bool firstRoundCostCheck = true;
  // The view offsets measured after the part of each view's difference that the map's error
  // explains is taken out (view_offsets.cpp, removeViewOffsets); off: `depth_bench --no-offset-slope-correction`.
  bool offsetSlopeCorrection = true;
  // Each view offset kept only where it exceeds what a map error could make (view_offsets.cpp,
  // kOffsetMapErrorPx): `depth_bench --offset-shrink`. Better development means before
  // offsetResidualCheck, but a sheen on texture is shrunk too (the view offsets' tests fail with it).
  bool offsetShrink = false;
  // The view offsets removed at full resolution only where, at half resolution, they left the views
  // agreeing no worse than before, within a tolerance (view_offsets.cpp, offsetsKept); off: `depth_bench
  // --no-offset-residual-check`.
  bool offsetResidualCheck = true;
  // Views matched at the reference view ((nu - 1) / 2, (nv - 1) / 2), the grid of the guides and of
  // the map, rather than at the aperture centre, half a view step away with an even number of
  // views (the same with an odd number): `depth_bench --match-at-reference`. Development means
  // 1.685 -> 1.358 % at 128 px but 1.903 -> 2.291 % at 256 (noisy thin bars 4.43 -> 7.32, glossy
  // weak texture 3.12 -> 6.09), with the defaults chosen for matching at the aperture centre.
  bool matchAtReference = false;
  // Every ringStep-th ring of views around the reference in the star (cost volume, fine search):
  // `depth_bench --star-ring-step 2` matches rings 2 and 4 of 9 x 9 views, half the star's 32.
  int starRingStep = 1;
  // Rounds of refinement and cleanup in the half-resolution passes of the view offsets (0: as
  // DepthOptions::refineRounds): `depth_bench --half-resolution-rounds 1`.
  int halfResolutionRounds = 0;
  // Noisy views: the half-resolution cost added where texture is weak (depth.cpp, addCoarseCost);
  // off: `depth_bench --no-coarse-cost`.
  bool noisyCoarseCost = true;
  // Shown each stage's map as it leaves it, at every resolution and pass the estimator runs (a
  // coarse pass's maps are smaller; noisy views are matched twice, the second pass last): "cost",
  // the aggregated cost's lowest label; "optimised"; then per round of refinement and cleanup
  // "refined N", "filled N", "reclaimed N", "median N". Where an error enters:
  // `depth_bench --stages`.
  std::function<void(const std::string& stage, const Image& disparity)> observeStage;
  // Told as each stage ends, in the order they run, so that a caller can time them (`depth_bench
  // --timings`): "views" (a pass's views made ready: luminance, offsets, smoothing), "cost" (stages 2-3), "optimised",
  // per round "refined N", "filled N", "reclaimed N", "median N", then "confidence"; every pass.
  std::function<void(const std::string& stage)> stageEnded;
};

Result<DepthMap> estimateDepth(const LightField& lightField, const DepthOptions& options,
                               const DepthExperiment& experiment);

}  // namespace lfcam::edof
