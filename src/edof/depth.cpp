// Depth from a light field (depth.hpp): the seven stages of depth.hpp in order, numbered alike
// below: the cost volume and its aggregation (cost_volume.cpp), semi-global optimisation,
// sub-label read-out, fine search (fine_search.cpp), cleanup, confidence; before them the views'
// brightness offsets (view_offsets.cpp) and the automatic prefilter; distances.
#include "lfcam/edof/depth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>

#include "core/parabola.hpp"
#include "core/parallel.hpp"
#include "core/quadratic_filter.hpp"
#include "edof/depth_experiment.hpp"
#include "edof/depth_stages.hpp"
#include "edof/edof_internal.hpp"
#include "edof/interpolation_terms.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam {

namespace {

using edof::aggregatedCost, edof::centralDifferences, edof::fullResolution, edof::halfResolution, edof::offsetsKept,
    edof::refineDisparity, edof::removeViewOffsets, edof::Residual, edof::sampleHalfResolution, edof::StarView,
    edof::starViews, edof::stepsU, edof::stepsV;

// Edge-aware fill of the pixels whose fine search was unsure (depth.hpp, step 6): each disparity
// weighted by the curvature of its fine-search cost at the minimum (flat where there is no
// texture) over the cost left there (high where no disparity makes the views agree, as at
// occlusions), both relative to their means; the fast global smoother guided by the centre view
// in colour, so that edges of hue separate surfaces as well as edges of brightness. Its strength
// (DepthOptions::fillLambda) chosen on the development scenes once the cleanup followed slopes:
// 0.15, 0.25, 0.35, 0.5 gave means of 1.88, 1.86, 1.89, 1.93 % at 128 px per view and 3.25, 3.23,
// 3.24, 3.30 % at 256 (longer reaches, 5 to 500, were worse in an earlier round).
void fillUncertain(const Image& guide, const std::vector<float>& curvature, const std::vector<float>& residual,
                   const DepthOptions& options, float* disparity) {
  const std::size_t n = std::size_t(guide.width()) * guide.height();
  double meanCurvature = 0, meanResidual = 0;
  for (std::size_t p = 0; p < n; ++p) meanCurvature += curvature[p], meanResidual += std::max(residual[p], 0.0f);
  meanCurvature = std::max(meanCurvature / double(n), 1e-20);
  meanResidual = std::max(meanResidual / double(n), 1e-20);
  std::vector<float> confidence(n);
  for (std::size_t p = 0; p < n; ++p)
    confidence[p] = float(curvature[p] / meanCurvature / (std::max(residual[p], 0.0f) / meanResidual + 0.5));
  edof::globalSmooth(guide.plane(0), guide.channels(), guide.width(), guide.height(), confidence.data(), disparity,
                     float(options.fillLambda), float(std::max(options.fillSigma, 1e-6)), /*iterations=*/3);
}

// The cost volume's veto of the occlusion edges' reclaim (depthStages), asked after the first round,
// and in the first for parts narrower than the band only. The margin, for the later rounds, chosen
// on the development scenes as the only one not worse at either size: mean BadPix(0.07) without the
// veto 2.37 % at 128 px per view, 2.77 % at 256 (`depth_bench --no-reclaim-cost-check [--size 256]`);
// margin 1: 2.21, 2.77 % (`--no-first-round-cost-check`; narrow near parts 15.4 -> 12.7 % at 128,
// 6.0 -> 5.4 % at 256). Measured with a temporary switch, not kept: margin 0.5:
// 2.18, 2.82 %; 2: 2.37, 2.76 %; the same veto for every pixel of the first round too: 2.00 and
// 2.82 % (the glossy weak card 8.8 -> 10.6 % at 256: there the aggregated cost itself carries the
// fattening the first reclaim removes).
constexpr double kReclaimCostMargin = 1.0;

// An aggregated cost volume at half the resolution (ns x nt, the same labels): that of the view
// offsets' last half-resolution map (estimateDepth), whose views have a quarter of the noise variance.
struct CoarseCost {
  edof::CostVolume volume;
  int ns = 0, nt = 0;
};

// Noisy views (the automatic prefilter's second match): the coarse cost, upsampled, added to the
// full resolution's with a weight of kNoisyCoarseWeight where the centre view has no texture above
// its noise, less where it has (1 / (1 + texture / (kNoisyCoarseTexture noise))), texture the mean
// squared gradient over a box of radius 2 less the noise's share. At twice the pixels per view,
// Lytro-like noise outweighs the texture of weakly textured regions in the full resolution's cost,
// and its minimum wanders there (blobs of error on the noisy people's backdrop), while the coarse
// cost, averaged over 2 x 2 pixels before matching, still has the texture's minimum; where texture
// is strong the full resolution's keeps its edges. Chosen on the development scenes' four noisy
// ones at 128 and 256 px per view among weights 0.25, 0.5 and 1 everywhere and 0.5 and 1 gated by
// 0.25, 1 and 4; kept as the only one better at both sizes (design.md, "Depth").
constexpr double kNoisyCoarseWeight = 0.5, kNoisyCoarseTexture = 0.25;

void addCoarseCost(const CoarseCost& coarse, const LightField& grey, const edof::ViewNoise& noise,
                   edof::CostVolume& cost) {
  const int ns = grey.ns(), nt = grey.nt(), labels = int(cost.size() / grey.shape().viewPixels());
  const std::size_t n = grey.shape().viewPixels();
  const Image centre = grey.subApertureImage((grey.nu() - 1) / 2, (grey.nv() - 1) / 2);
  std::vector<float> dx(n), dy(n), energy(n), texture(n), weight(n);
  centralDifferences(centre.plane(0), ns, nt, 1.0f, dx.data(), dy.data());
  for (std::size_t p = 0; p < n; ++p) energy[p] = dx[p] * dx[p] + dy[p] * dy[p];
  boxFilter(energy.data(), texture.data(), ns, nt, 2);
  for (std::size_t p = 0; p < n; ++p) {
    const double signal = std::max(double(texture[p]) - noise.variance, 0.0);
    weight[p] = float(kNoisyCoarseWeight / (1 + signal / (kNoisyCoarseTexture * noise.variance)));
  }
  parallelFor(0, std::size_t(labels), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t l = begin; l < end; ++l) {
      const float* half = coarse.volume.data() + l * std::size_t(coarse.ns) * coarse.nt;
      float* full = cost.data() + l * n;
      for (int y = 0; y < nt; ++y)
        for (int x = 0; x < ns; ++x) {
          const std::size_t p = std::size_t(y) * ns + x;
          full[p] += weight[p] * sampleHalfResolution(half, coarse.ns, coarse.nt, x, y);
        }
    }
  });
}

// The star of views the experiment asks for (DepthExperiment::matchAtReference, ::starRingStep).
edof::StarChoice starOf(const edof::DepthExperiment& experiment) {
  return {experiment.matchAtReference, experiment.starRingStep};
}

// Each pixel's mean cost and contrast (mean less lowest) over the labels of a pixel-major volume,
// and the typical depth of a cost minimum (the contrast's mean, summed in pixel order): the scale
// of the penalties and of the confidence.
struct CostContrast {
  std::vector<float> mean, contrast;
  double scale = 0;
};

CostContrast costContrast(const edof::CostVolume& volume, std::size_t n, int labels) {
  CostContrast out{std::vector<float>(n), std::vector<float>(n)};
  parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      const float* c = &volume[p * labels];
      double sum = 0;
      float lowest = c[0];
      for (int l = 0; l < labels; ++l) sum += c[l], lowest = std::min(lowest, c[l]);
      out.mean[p] = float(sum / labels);
      out.contrast[p] = out.mean[p] - lowest;
    }
  });
  double contrastSum = 0;
  for (std::size_t p = 0; p < n; ++p) contrastSum += out.contrast[p];
  out.scale = std::max(contrastSum / double(n), 1e-12);
  return out;
}

// Step 4 on a pixel-major cost volume: each pixel's label, fractional between labels, and the gain
// its costs were scaled by (`volume` is left scaled).
struct Optimised {
  std::vector<float> label, gain;
};

Optimised optimise(edof::CostVolume& volume, int ns, int nt, int labels, const CostContrast& costs, const Image& guide,
                   const DepthOptions& options) {
  const std::size_t n = std::size_t(ns) * nt;
  const double scale = costs.scale;
  Optimised out{std::vector<float>(n), std::vector<float>(n, 1.0f)};
  std::vector<float>& label = out.label;
  std::vector<float>& gain = out.gain;
  // Penalties that follow the cost's contrast near each pixel: image-wide ones outweigh the faint
  // evidence of weak texture, so a confident surface's disparity runs over a weakly textured one
  // beside it for as long as that evidence takes to add up to a jump (halos several pixels wide
  // where texture is coarse). Each pixel's costs are scaled by sqrt(image contrast / local
  // contrast), the penalties' scale the geometric mean of both; the parabola below does not see
  // the scaling, the confidence undoes it.
  if (options.smoothness > 0 && options.contrastRadius > 0) {
    std::vector<float> local(n);
    boxFilter(costs.contrast.data(), local.data(), ns, nt, options.contrastRadius);
    parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
      for (std::size_t p = begin; p < end; ++p) {
        gain[p] = float(std::sqrt(scale / std::max(double(local[p]), 1e-3 * scale)));
        for (int l = 0; l < labels; ++l) volume[p * labels + l] *= gain[p];
      }
    });
  }
  if (options.smoothness > 0) {
    // A small step penalty: slanted surfaces climb one label at a time (the fine search, step 5,
    // then smooths the steps); a large one for jumps, lowered across intensity edges.
    const float p1 = float(0.01 * scale * options.smoothness), p2 = float(0.6 * scale * options.smoothness);
    const edof::CostVolume summed =
        edof::semiGlobalMatching(volume, ns, nt, labels, guide.plane(0), p1, p2, /*edgeScale=*/0.01f);
    edof::winnerTakesAll(summed, ns, nt, labels, label.data());
    // Between labels: the parabola through the aggregated (not optimised) cost around the
    // optimiser's label, whose curve is not flattened by the penalties.
    parallelFor(0, n, 4096, [&](std::size_t begin, std::size_t end) {
      for (std::size_t p = begin; p < end; ++p) {
        const int best = std::clamp(int(std::lround(label[p])), 0, labels - 1);
        const float* c = &volume[p * labels];
        double offset = 0;
        if (best > 0 && best + 1 < labels) offset = parabolaVertex(c[best - 1], c[best], c[best + 1]);
        label[p] = float(best + offset);
      }
    });
  } else {
    edof::winnerTakesAll(volume, ns, nt, labels, label.data());
  }
  return out;
}

// Stages 2-7 (depth.hpp) on `grey`, the sRGB luminance the views are matched on, steered by
// `guide` (its centre view before any prefilter) and `colours`, the centre view's sRGB colours.
// `noise`: that of `grey`'s samples, whose loss under interpolation the costs add back.
// `residual`: the first fine search's. `coarseIn`: the half resolution's cost, added on noisy views
// (addCoarseCost); `coarseOut`: this one's aggregated cost, `coarseIn`'s added.
DepthMap depthStages(const Image& colours, const LightField& grey, const Image& guide,
                     const std::vector<double>& disparities, const DepthOptions& options,
                     const edof::DepthExperiment& experiment, const edof::ViewNoise& noise, Residual* residualOut,
                     const CoarseCost* coarseIn = nullptr, CoarseCost* coarseOut = nullptr) {
  const int ns = grey.ns(), nt = grey.nt(), labels = int(disparities.size());
  const std::size_t n = grey.shape().viewPixels();
  const double dmin = disparities.front(), dmax = disparities.back(), step = (dmax - dmin) / (labels - 1);
  const edof::GuidedFilter filter(guide.plane(0), ns, nt, std::max(options.filterRadius, 0),
                                  std::max(options.filterEpsilon, 1e-12));
  const double locking = std::max(experiment.lockingCorrection, 0.0);
  // A map of labels (fractional between them) in disparity.
  const auto writeDisparities = [&](const std::vector<float>& labelOf, Image& map) {
    for (std::size_t p = 0; p < n; ++p) map.plane(0)[p] = float(dmin + labelOf[p] * step);
  };
  // 2. Cost: the correspondence cue over each subset of views, less the defocus cue (the
  // full-aperture photograph at each label, sharpest where it is right); 3. aggregation: guided
  // filter per slice, steered by the reference view; the lowest subset.
  edof::CostVolume cost =
      aggregatedCost(grey, disparities, filter, options.defocusWeight, locking, noise, experiment.aggregateSubsetsApart,
                     experiment.defocusCeiling, experiment.oneDimensionalGate, starOf(experiment));
  if (coarseIn && !coarseIn->volume.empty() && noise.variance > 0 && experiment.noisyCoarseCost)
    addCoarseCost(*coarseIn, grey, noise, cost);
  if (experiment.stageEnded) experiment.stageEnded("cost");

  // Pixel-major for the optimisation, kBlock pixels at a time: a block's run in every label's plane
  // read in order, its part of the volume (kBlock x labels floats) staying in cache while written
  // across (a pixel at a time, the label planes' reads strided over the whole volume, took twice as long).
  edof::CostVolume volume(n * labels);
  constexpr std::size_t kBlock = 256;
  parallelFor(0, (n + kBlock - 1) / kBlock, 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t block = begin; block < end; ++block) {
      const std::size_t first = block * kBlock, last = std::min(n, first + kBlock);
      for (int l = 0; l < labels; ++l) {
        const float* plane = cost.data() + std::size_t(l) * n;
        for (std::size_t p = first; p < last; ++p) volume[p * labels + l] = plane[p];
      }
    }
  });
  if (experiment.observeStage) {
    std::vector<float> lowest(n);
    edof::winnerTakesAll(volume, ns, nt, labels, lowest.data());
    Image map(ns, nt, 1);
    writeDisparities(lowest, map);
    experiment.observeStage("cost", map);
  }
  if (coarseOut) *coarseOut = {std::move(cost), ns, nt};  // no longer needed here: handed over, not copied
  cost.clear();
  cost.shrink_to_fit();
  const CostContrast costs = costContrast(volume, n, labels);
  const std::vector<float>& meanCost = costs.mean;
  const double scale = costs.scale;
  // 4. Regularisation: semi-global optimisation, then the read-out between labels.
  const Optimised optimised = optimise(volume, ns, nt, labels, costs, guide, options);
  const std::vector<float>& label = optimised.label;
  const std::vector<float>& gain = optimised.gain;

  DepthMap result{Image(ns, nt, 1), Image(ns, nt, 1), dmin, dmax, labels};
  // The fine search may step past the ends of the range searched, and the cleanup, carrying
  // disparities along slopes, reach past them; the map stays inside it.
  const auto keepInRange = [&] {
    for (std::size_t p = 0; p < n; ++p)
      result.disparity.plane(0)[p] = std::clamp(result.disparity.plane(0)[p], float(dmin), float(dmax));
  };
  writeDisparities(label, result.disparity);
  const auto observe = [&](const std::string& stage) {
    if (experiment.stageEnded) experiment.stageEnded(stage);
    if (experiment.observeStage) experiment.observeStage(stage, result.disparity);
  };
  observe("optimised");
  // The cost volume's word on a move of the occlusion edges' reclaim: its aggregated cost (as the
  // optimisation saw it) at the farther disparity may exceed that at the pixel's own by at most
  // kReclaimCostMargin times the pixel's cost contrast. Run again from the boundary the first round
  // left, the reclaim ate narrow near parts of the background's colour (a finger's width within its
  // band), which the cost, on their texture, tells apart. In the first round only for a part
  // narrower than the band (no voter of its own surface beyond it): elsewhere the first reclaim
  // removes fattening that the aggregated cost carries too (development means 2.21 -> 2.02 % at 128
  // px per view, 2.78 -> 2.61 % at 256: narrow near parts 12.7 -> 9.1 % and 5.4 -> 4.0 %, the glossy
  // weak card 8.9 -> 7.1 % at 256; without: `depth_bench --no-first-round-cost-check`).
  const auto costAllows = [&](std::size_t p, float from, float to) {
    const float* c = &volume[p * labels];
    const auto at = [&](float d) {
      const double l = std::clamp((d - dmin) / step, 0.0, double(labels - 1));
      const int i = std::min(int(l), labels - 2);
      return c[i] + (l - i) * (c[i + 1] - c[i]);
    };
    const double scaledContrast = gain[p] * meanCost[p] - *std::min_element(c, c + labels);
    return at(to) - at(from) <= kReclaimCostMargin * scaledContrast;
  };
  // 5-6. Refinement and cleanup, `refineRounds` times: each round's fine search starts from the
  // map the previous round cleaned, a window's slices then follow the surface where the first
  // round's outliers (a slant's far end, a curved surface's outline) had bent them, and searches
  // at half the previous spacing (two rounds against one: development means 1.98 -> 1.65 % at
  // 128 px, 3.02 -> 2.60 % at 256; a third round at a quarter: 1.94 % at 128).
  std::vector<float> curvature(n, 1.0f), residual(n, 0.0f);
  *residualOut = {};
  const edof::GuidedFilter refineFilter(guide.plane(0), ns, nt, std::max(options.refineRadius, 0),
                                        std::max(options.filterEpsilon, 1e-12));
  const int rounds = options.refineSteps > 0 ? std::max(options.refineRounds, 1) : 1;
  for (int round = 0; round < rounds; ++round) {
    float* map = result.disparity.plane(0);
    // 5. Refinement: the fine search around the map.
    if (options.refineSteps > 0) {
      // Slices that follow a smoothed map: the fine search moves a whole window by one offset, so
      // it keeps the optimised map's own steps (labels climbing a slanted surface); a local fit
      // follows the slant without them. Only where it stays within a label of the map, so
      // occlusion edges keep their jumps (measured on antinous: floor 5.4 -> 4.5 points of
      // BadPix(0.07)). A quadratic fit, not a mean: a mean sags on a curved surface (a column, a
      // face) towards its far side, and the search, a fraction of a label wide, keeps some of that
      // (development scenes 1.81 -> 1.79 % at 128 px, 3.05 -> 3.00 % at 256; BadPix(0.03) 5.60 ->
      // 5.29 and 8.55 -> 7.89 %). Later rounds start from a cleaned map, which has no steps.
      if (round == 0 && options.refineSmoothRadius > 0) {
        std::vector<float> smooth(n);
        quadraticFitFilter(map, smooth.data(), ns, nt, options.refineSmoothRadius);
        for (std::size_t p = 0; p < n; ++p)
          if (std::abs(smooth[p] - map[p]) <= step) map[p] = smooth[p];
      }
      // A quarter of the correction in the fine search: its slices, a fraction of a label apart,
      // see far smaller differences of blur (measured on antinous: 1 there is worse than none).
      refineDisparity(grey, refineFilter, map, step / options.refineSteps / double(1 << round), options.refineSteps,
                      0.25 * std::max(experiment.lockingCorrection, 0.0), noise, experiment.refineAggregateHalves,
                      experiment.oneDimensionalGate, starOf(experiment), curvature.data(), residual.data());
      keepInRange();
      observe("refined " + std::to_string(round + 1));
      // The first round's residual, the one the automatic prefilter's threshold was chosen on.
      if (round == 0) {
        std::vector<float> sorted(residual);
        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
        *residualOut = {residual, sorted[sorted.size() / 2]};
      }
    }
    // 6. Cleanup: the edge-aware fill, occlusion edges, the weighted median, each guided by the
    // centre view's sRGB colours.
    if (options.fillLambda > 0 && options.refineSteps > 0) fillUncertain(colours, curvature, residual, options, map);
    observe("filled " + std::to_string(round + 1));
    if (round == 0 || experiment.reclaimEveryRound) {
      const bool checked = experiment.reclaimCostCheck && labels > 1 && (round > 0 || experiment.firstRoundCostCheck);
      edof::reclaimOcclusionEdges(colours, options.occlusionBand, experiment.slantedCleanup, map,
                                  [&](std::size_t p, float from, float to, int ownVoters) {
                                    return !checked || (round == 0 && ownVoters > 0) || costAllows(p, from, to);
                                  });
    }
    observe("reclaimed " + std::to_string(round + 1));
    if (options.medianRadius > 0)
      edof::guidedWeightedMedian(colours, options.medianRadius, float(std::max(options.medianSigma, 1e-6)),
                                 experiment.slantedCleanup, map);
    keepInRange();
    observe("median " + std::to_string(round + 1));
  }
  // 7. Confidence.
  for (std::size_t p = 0; p < n; ++p) {
    const int chosen = std::clamp(int(std::lround(label[p])), 0, labels - 1);
    const double depthOfMinimum = meanCost[p] - volume[p * labels + chosen] / gain[p];
    result.confidence.plane(0)[p] = float(std::clamp(1.0 - std::exp(-std::max(depthOfMinimum, 0.0) / scale), 0.0, 1.0));
  }
  if (experiment.stageEnded) experiment.stageEnded("confidence");
  return result;
}

// Automatic prefilter (DepthOptions::prefilterSigma -1): the views count as noisy when the fine
// search's median residual (DepthMap::viewResidual) exceeds kNoisyResidual, the geometric middle
// between the development scenes without noise (up to 7.5e-6) and those with Lytro-like noise
// (from 2.4e-4; pixel-scale texture reads as noisy too); they are then smoothed by
// kNoisyPrefilterSigma, chosen on the development scenes (`depth_bench` prints both per scene).
constexpr double kNoisyResidual = 4e-5, kNoisyPrefilterSigma = 0.55;

// The share of a view's noise variance that bilinear sampling keeps, V kept(fx) kept(fy), averaged
// over the labels: with the fractions of the shifts spread evenly, 2/3 along an axis the view is
// shifted on (`uc`, `vc` view steps from where the views are matched) and 1 along one it is not.
double meanKept(double uc, double vc) { return (uc != 0 ? 2.0 / 3 : 1.0) * (vc != 0 ? 2.0 / 3 : 1.0); }

// The noise of views smoothed by a Gaussian of `sigma`, from `residual`, the median cost of their
// match as given: at the right disparity, the noise variance V kept by the reference's samples
// (`referenceKept`: 1 unless it is resampled, as with an even number of views matched at the
// aperture centre) plus that kept by an interpolated view's, so the residual is V (referenceKept +
// the mean kept over the star's views). Smoothing multiplies the variance by the sum of the squared
// taps along each axis and correlates neighbours.
edof::ViewNoise smoothedNoise(double residual, double sigma, const std::vector<StarView>& views, double referenceKept) {
  double kept = 0;
  for (const StarView& view : views) kept += meanKept(view.uc, view.vc);
  kept /= double(std::max<std::size_t>(views.size(), 1));
  const std::vector<float> taps = edof::gaussianTaps(sigma);
  double lag0 = 0, lag1 = 0;
  for (std::size_t i = 0; i < taps.size(); ++i) {
    lag0 += double(taps[i]) * taps[i];
    if (i + 1 < taps.size()) lag1 += double(taps[i]) * taps[i + 1];
  }
  return {residual / (referenceKept + kept) * lag0 * lag0, lag1 / lag0};
}

// The matching light field of DepthExperiment::gradientWeight a: channels sqrt(1 - a) I,
// sqrt(a) dI/dx, sqrt(a) dI/dy (central differences), so that the squared difference summed over
// channels is (1 - a) dI^2 + a |d grad I|^2.
LightField withGradients(const LightField& grey, double weight) {
  LightFieldShape shape = grey.shape();
  shape.channels = 3;
  LightField out(shape);
  out.metadata = grey.metadata;
  const int ns = grey.ns(), nt = grey.nt();
  const float intensity = float(std::sqrt(1 - weight)), gradient = float(std::sqrt(weight));
  parallelFor(0, shape.views(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view) {
      const int u = int(view % grey.nu()), v = int(view / grey.nu());
      const float* in = grey.plane(u, v, 0);
      float* level = out.plane(u, v, 0);
      for (std::size_t p = 0; p < grey.shape().viewPixels(); ++p) level[p] = intensity * in[p];
      centralDifferences(in, ns, nt, gradient, out.plane(u, v, 1), out.plane(u, v, 2));
    }
  });
  return out;
}

// Every view smoothed by a Gaussian of `sigma` pixels: sensor noise is white, while the views of
// a plenoptic camera are band-limited by its microlenses, so a light smoothing removes more noise
// than detail.
void blurViews(LightField& grey, double sigma) {
  parallelFor(0, grey.shape().views(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view)
      for (int c = 0; c < grey.channels(); ++c)
        edof::gaussianBlur(grey.plane(int(view % grey.nu()), int(view / grey.nu()), c), grey.ns(), grey.nt(), sigma);
  });
}

}  // namespace

Result<DepthMap> estimateDepth(const LightField& lightField, const DepthOptions& options) {
  return edof::estimateDepth(lightField, options, {});
}

Result<DepthMap> edof::estimateDepth(const LightField& lightField, const DepthOptions& options,
                                     const DepthExperiment& experiment) {
  if (lightField.empty() || lightField.ns() < 2 || lightField.nt() < 2)
    return makeError(ErrorCode::Usage, "depth: the light field is empty");
  if (lightField.nu() * lightField.nv() < 2)
    return makeError(ErrorCode::Usage, "depth: the light field has a single view, so no parallax to measure");
  const double dmin = options.disparityMin.value_or(lightField.metadata.disparityMin.value_or(-2.0));
  const double dmax = options.disparityMax.value_or(lightField.metadata.disparityMax.value_or(2.0));
  if (!(std::isfinite(dmin) && std::isfinite(dmax) && dmin < dmax))
    return makeError(ErrorCode::Usage, "depth: the disparity range [" + std::to_string(dmin) + ", " +
                                           std::to_string(dmax) + "] is empty");
  // 1. Range: the candidate disparities.
  int labels = options.labels;
  if (labels <= 0) labels = std::clamp(int(std::ceil((dmax - dmin) / 0.1)) + 1, 16, 96);
  if (labels < 2) return makeError(ErrorCode::Usage, "depth: at least 2 candidate disparities are needed");
  std::vector<double> disparities(labels);
  const double step = (dmax - dmin) / (labels - 1);
  for (int l = 0; l < labels; ++l) disparities[l] = dmin + l * step;

  // Matching on sRGB-encoded luminance: roughly uniform in perceived contrast, so that texture in
  // the shadows counts as much as in the light (in linear light it nearly vanishes).
  LightField grey = edof::luminanceLightField(lightField);
  parallelFor(0, grey.samples().size(), 1 << 16, [&](std::size_t begin, std::size_t end) {
    const std::span<float> samples(grey.samples().data() + begin, end - begin);
    for (float& v : samples) v = std::max(v, 0.0f);
    srgbFromLinear(samples);
  });
  const Image guide = grey.subApertureImage((grey.nu() - 1) / 2, (grey.nv() - 1) / 2);
  // The centre view's colours (linear) that steer the cleanup, sRGB-encoded as the matching.
  const Image centre = lightField.subApertureImage((grey.nu() - 1) / 2, (grey.nv() - 1) / 2);
  const auto srgb = [](Image image) {
    for (float& v : image.pixels()) v = std::max(v, 0.0f);
    srgbFromLinear(image.pixels());
    return image;
  };
  const Image colours = srgb(centre.copy());
  if (experiment.highPassRadius > 0)
    parallelFor(0, grey.shape().views(), 1, [&](std::size_t begin, std::size_t end) {
      std::vector<float> mean(grey.shape().viewPixels());
      for (std::size_t view = begin; view < end; ++view) {
        float* plane = grey.plane(int(view % grey.nu()), int(view / grey.nu()), 0);
        boxFilter(plane, mean.data(), grey.ns(), grey.nt(), experiment.highPassRadius);
        for (std::size_t i = 0; i < mean.size(); ++i) plane[i] -= mean[i];
      }
    });
  if (experiment.gradientWeight > 0) grey = withGradients(grey, experiment.gradientWeight);
  const double prefilter = options.prefilterSigma;
  if (prefilter > 0) blurViews(grey, prefilter);
  Residual residual;
  CoarseCost coarse;
  // View offsets: first maps at half resolution, each pass matching views whose offsets the
  // previous one removed; the last one's offsets removed from the views at full resolution (views
  // under 4 pixels across: none).
  if (options.offsetRadius > 0 && options.offsetPasses > 0 && grey.ns() >= 4 && grey.nt() >= 4) {
    const Image smallColours = srgb(halfResolution(centre));
    LightField small = halfResolution(grey);
    const Image smallGuide = small.subApertureImage((small.nu() - 1) / 2, (small.nv() - 1) / 2);
    std::vector<double> halved(disparities);
    for (double& d : halved) d *= 0.5;
    DepthOptions halfOptions = options;
    if (experiment.halfResolutionRounds > 0) halfOptions.refineRounds = experiment.halfResolutionRounds;
    Image first;
    Residual withoutOffsets;
    for (int pass = 0; pass < options.offsetPasses; ++pass) {
      if (pass > 0)
        removeViewOffsets(small, first, std::max(options.offsetRadius / 2, 1), options.offsetEpsilon / 4,
                          experiment.offsetSlopeCorrection, experiment.offsetShrink, experiment.matchAtReference);
      if (experiment.stageEnded) experiment.stageEnded("views");
      CoarseCost* keep = pass + 1 == options.offsetPasses ? &coarse : nullptr;
      first =
          depthStages(smallColours, small, smallGuide, halved, halfOptions, experiment, {}, &residual, nullptr, keep)
              .disparity;
      if (pass == 0) withoutOffsets = std::move(residual);
    }
    const bool checked = experiment.offsetResidualCheck && options.offsetPasses > 1 && !residual.perPixel.empty();
    const std::vector<float> kept =
        checked ? offsetsKept(withoutOffsets, residual.perPixel, small.ns(), small.nt(), grey.ns(), grey.nt())
                : std::vector<float>{};
    removeViewOffsets(grey, fullResolution(first, grey.ns(), grey.nt()), options.offsetRadius, options.offsetEpsilon,
                      experiment.offsetSlopeCorrection, experiment.offsetShrink, experiment.matchAtReference,
                      checked ? &kept : nullptr);
  }
  if (experiment.stageEnded) experiment.stageEnded("views");
  DepthMap map = depthStages(colours, grey, guide, disparities, options, experiment, {}, &residual, &coarse);
  map.prefilterSigma = std::max(prefilter, 0.0);
  map.viewResidual = prefilter > 0 ? 0.0 : residual.median;  // of the views as given only
  // Automatic: the views matched as they are, then, where they disagree at their best match by
  // more than clean views do (noise, or texture finer than the pixels), smoothed and matched again.
  if (prefilter < 0 && residual.median > kNoisyResidual) {
    blurViews(grey, kNoisyPrefilterSigma);
    if (experiment.stageEnded) experiment.stageEnded("views");
    const double asGiven = map.viewResidual;
    const int referenceU = (grey.nu() - 1) / 2, referenceV = (grey.nv() - 1) / 2;
    const bool atReference = experiment.matchAtReference;
    const edof::ViewNoise noise =
        experiment.noiseCorrection
            ? smoothedNoise(asGiven, kNoisyPrefilterSigma, starViews(grey, referenceU, referenceV, starOf(experiment)),
                            meanKept(stepsU(grey, referenceU, atReference), stepsV(grey, referenceV, atReference)))
            : edof::ViewNoise{};
    map = depthStages(colours, grey, guide, disparities, options, experiment, noise, &residual, &coarse);
    map.prefilterSigma = kNoisyPrefilterSigma;
    map.viewResidual = asGiven;
  }
  return map;
}

std::optional<double> distanceFromDisparity(const Optics& optics, double disparity) {
  if (!optics.focalLengthMm || !(*optics.focalLengthMm > 0) || !(optics.lensToMicrolensMm > 0)) return std::nullopt;
  const double alpha = optics.alphaFromSlope(disparity);
  const double film = alpha * optics.lensToMicrolensMm;
  const double inverse = 1.0 / *optics.focalLengthMm - 1.0 / film;  // 1/z = 1/f - 1/(alpha F)
  if (!(alpha > 0) || !(inverse > 0)) return std::numeric_limits<double>::infinity();
  return 1.0 / inverse;
}

std::optional<double> disparityFromDistance(const Optics& optics, double distanceMm) {
  if (!optics.focalLengthMm || !(*optics.focalLengthMm > 0) || !(optics.lensToMicrolensMm > 0) ||
      !(distanceMm > *optics.focalLengthMm))
    return std::nullopt;
  // Thin lens: the image of the surface lies at alpha F behind the lens.
  const double film = 1.0 / (1.0 / *optics.focalLengthMm - 1.0 / distanceMm);
  return optics.slopeFromAlpha(film / optics.lensToMicrolensMm);
}

Result<Image> distanceMap(const LightFieldMetadata& metadata, const Image& disparity) {
  if (!metadata.optics || !metadata.optics->focalLengthMm)
    return makeError(ErrorCode::Usage,
                     "depth: the light field carries no optics with a focal length, so no metric distance");
  Image out(disparity.width(), disparity.height(), 1);
  for (std::size_t i = 0; i < out.planeSize(); ++i)
    out.plane(0)[i] = float(distanceFromDisparity(*metadata.optics, disparity.plane(0)[i]).value_or(0.0));
  return out;
}

}  // namespace lfcam
