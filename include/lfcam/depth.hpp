// Depth from a light field: the disparity seen through the centre of the aperture, estimated from
// the two cues a plenoptic camera offers (Adelson and Wang 1992; Ng et al. 2005, section 5.2).
//
// Units and conventions are those of light_field.hpp: disparity ("slope") in pixels of (s, t) per
// view step, positive nearer than the plane in focus at capture; the map is ns x nt, one channel,
// in the pixel grid of the aperture centre.
//
// How estimateDepth works (src/edof/depth.cpp):
//  1. Candidate disparities ("labels"): evenly spaced over [disparityMin, disparityMax] from the
//     options, else from the light field's metadata, else [-2, 2].
//  2. Correspondence cue, per label d: each view of a star of views (the centre row, column and
//     both diagonals) is sampled at (s - u d, t - v d), bilinearly, and compared with the
//     reference (centre) view: squared difference of luminance, sRGB-encoded so that texture in
//     the shadows counts. At occlusion boundaries only part of the aperture sees the point, so
//     the squared differences are averaged over four strict half-apertures (u < 0, u > 0, v < 0,
//     v > 0: the views moving along an edge are left out, as they too see a slanted occluder),
//     and over the centre row and the centre column alone (for surfaces slanted steeply along
//     one axis, like a floor), and the best subset is kept. Bilinear sampling between pixels
//     blurs by f (1 - f) / 2 times the second difference at fraction f, which biases the cost
//     towards whole-pixel shifts; that term, modelled from the reference view's squared second
//     differences, can be subtracted (`lockingCorrection`, off by default; a quarter of it in the
//     fine search of step 6). (The light field's weight is not used here: a vignetted view counts like the others.)
//  3. Defocus cue, per label d: the photograph refocused at d (lfcam::refocus of the luminance,
//     every view) is sharpest where d is right; its squared Laplacian is subtracted from the cost,
//     weighted by `defocusWeight` (both terms are squared luminance).
//  4. Aggregation: each cost slice is smoothed by a guided filter (He et al. 2010) steered by the
//     centre view, which averages over a window without crossing intensity edges. With
//     `aggregateSubsetsApart` (on) each subset of step 2 is aggregated on its own (less the
//     defocus cue) and the lowest subset taken per label afterwards, as the fine search does,
//     labels four at a time so that memory stays that of one volume.
//  5. Regularisation: semi-global optimisation (Hirschmueller 2008) along 8 paths, with a small
//     penalty for a one-label step (slanted surfaces) and a large one for jumps, lowered across
//     intensity edges of the centre view. The optimiser's label per pixel, then a parabola through
//     the aggregated cost (step 4) at that label and its neighbours places it between labels.
//  6. Fine search (`refineSteps`): the cost of step 2 at the map's own disparity plus k / refineSteps
//     of a label step, k in [-refineSteps, refineSteps], per pixel, aggregated by a wider guided
//     filter (`refineRadius`) over slices that follow the map, and a parabola at the lowest. The
//     labels of steps 1-5 leave steps on slanted and curved surfaces, and the interpolation of
//     views biases the cost towards disparities of whole-pixel shifts; this removes both. The map
//     is first replaced by its local mean over (2 `refineSmoothRadius` + 1)^2 pixels wherever that
//     is within a label step of it, so that the slices follow a slanted surface without the
//     labels' steps (a window is moved by one offset) while occlusion edges keep their jumps.
//     With `refineAggregateHalves` each subset of views of step 2 is aggregated on its own and the
//     lowest taken per slice afterwards (a window keeps to one subset; a per-pixel minimum picks
//     whichever subset is lowest by chance at each pixel, a bias and noise).
//  7. Edge-aware fill (`fillLambda`, `fillSigma`): each disparity is weighted by the curvature of
//     its fine-search cost at the minimum (flat without texture) over the cost left there (high
//     where no disparity makes the views agree, as at occlusions), and the map replaced by its
//     confidence-weighted edge-aware average, neighbours linked by the likeness of their colours
//     in the centre view (the fast global smoother of Min et al. 2014): unsure pixels take
//     the disparity of sure ones on the same surface (on antinous it helps the wall; the floor,
//     slanted steeply, is beyond a fit that favours constant disparity).
//  7b. Occlusion edges (`occlusionBand`): pixels within that many pixels of a jump of the map move
//     to the farther surface when its pixels beyond the band, weighted by colour likeness in the
//     centre view, outweigh their own surface's (src/edof/occlusion_edges.cpp): where the
//     background has no texture only colour tells which surface a pixel shows, and the nearer
//     disparity spreads a few pixels onto it.
//  8. Weighted median (`medianRadius`, `medianSigma`): each disparity becomes the median of its
//     window weighted by likeness in the centre view (Ma et al. 2013), which removes isolated
//     mistakes and pulls occlusion edges back onto intensity edges.
//  9. Confidence in [0, 1]: 1 - exp(-(mean cost - chosen cost) / m), the aggregated costs of the
//     pixel, m the mean of (mean cost - lowest cost) over the image: 0 where every label is as
//     good (no texture), near 1 at a clear minimum.
//
// Metric distance: with Optics including focalLengthMm, a disparity d is the slope brought into
// focus by film depth alpha F with alpha = optics.alphaFromSlope(d) (Equation 6); the thin-lens
// equation 1/z + 1/(alpha F) = 1/f gives the distance z from the main lens to the plane in focus,
// in millimetres. Disparities at or beyond infinity give +infinity.
//
// Metric distance for HCI folders: parameters.cfg gives optics for which this is the benchmark's
// own disparity-to-depth conversion (hci_parameters.hpp).
//
// Measured (tests/depth_layered_planes_test.cpp, tests/realdata/hci_depth_test.cpp,
// tests/edof_people_test.cpp): BadPix(0.07) 5.5 %, MSE x100 6.7 on the layered-planes default
// scene (9x9 views of 128x128); 6.8 %, BadPix(0.03) 22.2 % and 6.0 on HCI antinous (what
// remains: the steep floor, biased too far where it has no texture, and occlusion edges;
// docs/design.md has the breakdown); 5.2 % and 0.95 on the simulator's people scene,
// noise-free (9x9 views of 80x80).
// Cost: labels x (33 views + one luminance refocus) bilinear passes over ns x nt, 8 passes of
// labels x ns x nt for the optimisation, (2 refineSteps + 1) x 33 bilinear passes for the fine
// search (and 6 x (2 refineSteps + 1) guided filters of its subsets; 6 x labels in the cost
// volume with aggregateSubsetsApart), 6 tridiagonal solves per
// row and per column for the fill (about 70 ms of CPU at 512x512) and a (2 medianRadius + 1)^2
// selection per pixel for the median; memory 2 x labels x ns x nt floats (the fine search's
// subsets 6 x (2 refineSteps + 1) x ns x nt more, the cost volume's 6 x 4 x ns x nt;
// bench/depth_bench.cpp: ratio to one refocus).
#pragma once

#include <optional>

#include "lfcam/image.hpp"
#include "lfcam/light_field.hpp"
#include "lfcam/result.hpp"

namespace lfcam {

struct DepthOptions {
  std::optional<double> disparityMin, disparityMax;  // default: metadata, else [-2, 2]
  int labels = 0;                 // candidate disparities; 0: one per 0.1 px, within [16, 96]
  double defocusWeight = 0.75;    // weight of the defocus cue against the correspondence cue
  int filterRadius = 1;           // guided filter window: (2 r + 1)^2 pixels
  double filterEpsilon = 3e-5;    // guided filter regulariser, squared linear luminance
  double smoothness = 0.7;        // scales both jump penalties of the optimisation; 0 disables it
  int refineSteps = 2;            // fine search: steps per label on each side; 0 disables it
  int refineRadius = 2;           // guided filter window of the fine search: (2 r + 1)^2 pixels
  int refineSmoothRadius = 2;     // local mean of the map the fine search starts from; 0: none
  bool refineAggregateHalves = true;  // fine search: aggregate each subset's cost, then the best
  bool aggregateSubsetsApart = true;  // cost volume: aggregate each subset's cost, then the best
  int occlusionBand = 3;          // background beside nearer surfaces reclaimed within it; 0: off
  int medianRadius = 5;           // weighted median window; 0 disables it
  double medianSigma = 0.05;      // guide (sRGB luminance) difference that weighs a neighbour 0.6
  double fillLambda = 1.0;        // edge-aware fill (needs refineSteps > 0); 0 disables it
  double fillSigma = 0.02;        // centre-view (sRGB) colour difference that weakens a link to 1/e
  // Scale of the interpolation-bias term removed from the cost; 0: none. Off by default: it took
  // antinous from 14.2 to 13.3 % BadPix(0.07) but the simulator's people scene from 17.9 to 47.2 %
  // (before refineAggregateHalves; with it, antinous 10.3 -> 10.4 %).
  double lockingCorrection = 0.0;
};

struct DepthMap {
  Image disparity;   // ns x nt, 1 channel, pixels per view step
  Image confidence;  // ns x nt, 1 channel, in [0, 1]
  double disparityMin = 0, disparityMax = 0;  // the range searched
  int labels = 0;
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
