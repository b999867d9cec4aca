// Depth from a light field: the disparity seen from its centre view, from the two
// cues a plenoptic camera offers (Adelson and Wang 1992; Ng et al. 2005, section 5.2). Scores
// against a ground truth: disparity_scores.hpp. Settings by name: depth_knobs.hpp. In 3D: point_cloud.hpp.
//
// Input: a light field of at least 2 views (light_field.hpp), its colour or luminance.
// Output: disparity ("slope") in pixels of (s, t) per view step, positive nearer than the plane
// in focus at capture, ns x nt in the pixel grid of the centre view; a confidence in [0, 1];
// distance in mm from the main lens when the optics are known (thin lens, Equation 6). The map is
// that of the centre view ((nu - 1) / 2, (nv - 1) / 2): with an even number of views, half a view
// step before the aperture's centre, where a surface at disparity d lies d / 2 pixels aside (the
// simulator's truth for it: idealDepthOfView, simulate.hpp).
//
// Stages (src/edof/depth.cpp, the larger in the files src/edof/depth_stages.hpp names; the same
// numbers; why each is there: docs/design.md, "Depth"):
//  1. Range: candidate disparities ("labels") evenly over [disparityMin, disparityMax] (options,
//     else the metadata, else [-2, 2]).
//  2. Cost per label: squared differences of sRGB luminance between the centre view and the views
//     of a star through it, sheared by the label, over subsets of views that an occluder leaves
//     out (four strict half-apertures, the centre row, the centre column); less the defocus cue
//     (squared Laplacian of the photograph refocused at the label, at most twice the centre
//     view's, `defocusWeight`).
//     Each view's brightness offset from the centre view (a sheen that changes across the
//     aperture) is removed first: stages 2-6 run at half resolution (`offsetPasses` times, each
//     on views the previous map aligned and corrected), the views are warped onto the centre view
//     by that map and their difference averaged by a guided filter the map steers (`offsetRadius`,
//     `offsetEpsilon`), after the part of it that an error of the map explains (the error, fitted
//     to all views over that radius, with a gain per view, times the centre view's gradient) is
//     taken out; at full resolution only where, at half, their removal left the views agreeing no
//     worse than before it, within a tolerance. Views that disagree at their best match (noise,
//     aliasing) are smoothed (`prefilterSigma`; automatic: stages 2-7 run once, and again on
//     smoothed views when the fine search's median residual says so, with the noise variance that
//     interpolating between pixels removes, estimated from that residual, added back to the cost).
//  3. Aggregation: a guided filter steered by the centre view (`filterRadius`, `filterEpsilon`),
//     each subset's cost apart, then the lowest subset per label (the centre row and column only
//     where their cost changes with disparity, or matches better than noise explains). On smoothed
//     noisy views, the last half-resolution pass's cost is added where texture is weak against
//     the noise.
//  4. Regularisation: semi-global optimisation along 8 paths (`smoothness`), the penalties scaled
//     at each pixel by the cost's contrast near it and over the image (`contrastRadius`), then a
//     parabola through the aggregated cost places each pixel between labels.
//  5. Refinement: a fine search of the stage-2 cost around a local quadratic fit of the map, a
//     fraction of a label apart (`refineSteps`, `refineRadius`, `refineSmoothRadius`), removing
//     the labels' steps on slanted surfaces and the bias of interpolated views towards whole-pixel
//     shifts.
//  6. Cleanup: an edge-aware fill of unsure pixels from sure ones of the same colour (`fillLambda`,
//     `fillSigma`), background given back beside nearer surfaces (`occlusionBand`), a weighted
//     median guided by the centre view, each neighbour carried along the map's slope
//     (`medianRadius`, `medianSigma`).
//     Steps 5 and 6 run `refineRounds` times, each fine search around the map the round before
//     cleaned, at half its spacing (the quadratic fit in the first round only). Background is
//     given back only where the stage-3 cost does not say otherwise: in the first round on parts
//     narrower than the band, after it everywhere.
//  7. Confidence: 1 - exp(-(mean cost - chosen cost) / m), m that margin's mean over the image.
//
// Cost: about labels x 34 bilinear passes over ns x nt and 8 optimisation paths (4 sweeps) over
// labels x ns x nt, and the half-resolution passes about half as much again; memory 2 x labels x ns
// x nt floats (bench/depth_bench.cpp: time, each stage's with --timings, and the scores table).
#pragma once

#include <optional>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

// The settings, stage by stage (the steps above); each is a flag of `lfcam depth` (depth_knobs.hpp).
struct DepthOptions {
  // 1. Range.
  std::optional<double> disparityMin, disparityMax;  // default: metadata, else [-2, 2]
  int labels = 0;                                    // candidate disparities; 0: one per 0.1 px, within [16, 96]
  // 2. Cost.
  double prefilterSigma = -1;   // views smoothed by a Gaussian of this sigma (px) before matching; 0: none;
                                // -1: automatic, 0.55 where the views are noisy, else none
  double defocusWeight = 0.4;   // weight of the defocus cue against the correspondence cue
  int offsetRadius = 16;        // views less their brightness offset from the centre view, averaged over
                                // about this radius (px); 0: none
  double offsetEpsilon = 1e-3;  // regulariser of that average's guided filter, squared disparity
  int offsetPasses = 2;         // first maps at half resolution that align the views for it
  // 3. Aggregation.
  int filterRadius = 1;         // guided filter window: (2 r + 1)^2 pixels
  double filterEpsilon = 3e-5;  // guided filter regulariser, squared linear luminance
  // 4. Regularisation.
  double smoothness = 0.4;  // scales both jump penalties of the optimisation; 0 disables it
  int contrastRadius = 4;   // window over which the cost's contrast sets the penalties' scale; 0: image-wide
  // 5. Refinement.
  int refineSteps = 2;         // fine search: steps per label on each side; 0 disables it
  int refineRadius = 1;        // guided filter window of the fine search: (2 r + 1)^2 pixels
  int refineSmoothRadius = 2;  // local quadratic fit of the map the first fine search starts from; 0 or 1: none
  int refineRounds = 2;        // rounds of fine search and cleanup (steps 5-6), each at half the spacing before
  // 6. Cleanup.
  double fillLambda = 0.25;   // edge-aware fill (needs refineSteps > 0); 0 disables it
  double fillSigma = 0.01;    // centre-view (sRGB) colour difference that weakens a link to 1/e
  int occlusionBand = 3;      // background beside nearer surfaces reclaimed within it; 0: off
  int medianRadius = 5;       // weighted median window; 0 disables it
  double medianSigma = 0.05;  // guide (sRGB luminance) difference that weighs a neighbour 0.6
};

struct DepthMap {
  Image disparity;                            // ns x nt, 1 channel, pixels per view step
  Image confidence;                           // ns x nt, 1 channel, in [0, 1]
  double disparityMin = 0, disparityMax = 0;  // the range searched
  int labels = 0;
  // How much the views, as given, disagree at the disparity found: the median over pixels of the
  // fine search's cost there (mean squared sRGB difference from the centre view); 0 without it.
  double viewResidual = 0;
  double prefilterSigma = 0;  // the smoothing the views were matched with (px; 0: none)
};

// Usage error for an empty light field or an empty/invalid disparity range.
Result<DepthMap> estimateDepth(const LightField& lightField, const DepthOptions& options = {});

// Distance (mm) from the main lens to the plane that a disparity brings into focus; +infinity at
// or beyond infinity; nullopt without a focal length.
std::optional<double> distanceFromDisparity(const Optics& optics, double disparity);
// The inverse: the disparity of a surface at `distanceMm` from the main lens (+infinity allowed);
// nullopt without a focal length or for a distance at or inside the focal length.
std::optional<double> disparityFromDistance(const Optics& optics, double distanceMm);
// The map of distances for a disparity map (mm; +infinity beyond infinity). Usage error without
// optics or focal length.
Result<Image> distanceMap(const LightFieldMetadata& metadata, const Image& disparity);

}  // namespace lfcam
