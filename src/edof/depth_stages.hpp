// The stages of depth estimation (include/lfcam/depth.hpp) that live in files of their own, for
// the pipeline in depth.cpp: the views matched and their subsets, the cost volume and its
// aggregation (steps 2-3, cost_volume.cpp), the fine search (step 5, fine_search.cpp), the half
// resolution (half_resolution.cpp) and the views' brightness offsets (view_offsets.cpp).
#pragma once

#include <cstddef>
#include <vector>

#include "edof/edof_internal.hpp"
#include "edof/interpolation_terms.hpp"
#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"

namespace lfcam::edof {

// Views, their subsets and the cost volume: steps 2-3 (cost_volume.cpp).

// Subsets of views compared separately, as bits (a view may belong to several): four strict
// half-apertures for occlusion boundaries, u < 0, u > 0, v < 0, v > 0; and the centre row and
// the centre column alone, for surfaces strongly slanted in depth along one axis (a floor seen at
// a grazing angle is foreshortened differently in every view of a column, not of a row). The
// halves leave out the centre row or column: next to a slanted occluding edge, the views that
// move along the edge see the occluder too (measured on antinous: MSE x100 28 -> 14).
constexpr int kHalves = 6;

struct StarView {
  int u = 0, v = 0;
  double uc = 0, vc = 0;  // view steps from the aperture centre
  int halves = 0;         // bit h set: the view is in half-aperture h
};

// View steps of view (u, v) from the point the views are matched at: the aperture centre, or with
// `fromReference` the reference view ((nu - 1) / 2, (nv - 1) / 2; DepthExperiment::matchAtReference).
// They differ with an even number of views.
double stepsU(const LightField& lightField, int u, bool fromReference);
double stepsV(const LightField& lightField, int v, bool fromReference);

// Which views the star takes and where they are matched: `fromReference` as stepsU's; every
// `ringStep`-th ring of views around the reference (1: all; DepthExperiment::starRingStep).
struct StarChoice {
  bool fromReference = false;
  int ringStep = 1;
};

// The views compared with the reference: the star through the reference view (its row, its
// column, both diagonals). A star sees every edge orientation from both sides with a third of
// the views of the full aperture.
std::vector<StarView> starViews(const LightField& lightField, int referenceU, int referenceV, StarChoice star);

// Bilinear interpolation blurs a view sampled between pixels, by f (1 - f) / 2 times the second
// difference of the signal at fraction f, and that blur adds its square to the cost of every
// disparity that shifts views by fractions: the cost is biased towards whole-pixel shifts
// ("pixel locking"). The model of that term: per pixel the squared second differences of the
// reference view (it shows the same texture), per view and disparity the weights from
// interpolationBlur (interpolation_terms.hpp); the cost subtracts their product. The reference's
// own interpolation (an even grid) is left out.
struct SecondDifferences {
  std::vector<float> xx, yy, xy;  // Ixx^2, Iyy^2, 2 Ixx Iyy
};

SecondDifferences secondDifferences(const float* plane, int ns, int nt);

// The subsets of views with at least one view (all six unless the aperture is a single row or
// column), and how many views each has.
std::vector<int> subsetsWithViews(const std::vector<StarView>& views, int (&viewsIn)[kHalves]);

// The best subset of views: at an occlusion boundary, the half-aperture that sees only the
// surface. out[p] = the lowest of `subsets` planes of n pixels, `stride` floats apart from `first`.
void lowestSubset(const float* first, std::size_t subsets, std::size_t stride, std::size_t n, float* out);

// Whether the one-dimensional subsets are gated (cost_volume.cpp, kOneDimensionalContrast): asked for (`wanted`:
// DepthExperiment::oneDimensionalGate), and all four half-apertures and both one-dimensional subsets have views
// (subsetsWithViews' order puts the halves first).
bool gatesOneDimensional(const std::vector<int>& subsets, bool wanted);

// Steps 3 and 5: the lowest aggregated cost per pixel and slice, `slices` planes of n pixels in
// `lowest` holding the half-apertures' lowest on entry; `oneDimensional`: each such subset's
// planes, n floats apart. Each joins the lowest where the gate lets it.
void joinOneDimensional(float* lowest, const std::vector<const float*>& oneDimensional, int slices, std::size_t n,
                        double noiseVariance);

// Aggregation: each plane in[k] filtered into out[k] (which may be in[k]) by the guided filter, in parallel.
void aggregatePlanes(const GuidedFilter& filter, const std::vector<const float*>& in, const std::vector<float*>& out);
// Each of `count` planes of n pixels replaced by its guided filter.
void aggregatePlanes(const GuidedFilter& filter, float* planes, std::size_t count, std::size_t n);

// Steps 2-3: per label, the correspondence cost of each subset of views less the defocus cue,
// aggregated, and the lowest subset kept. With `subsetsApart` each subset's slice is aggregated
// before the lowest is taken (the guided filter is linear, so the defocus cue is aggregated as
// on its own), as the fine search does (refineDisparity), and the one-dimensional subsets join
// it where joinOneDimensional lets them; else the lowest is taken per pixel first. `ceiling`: the
// defocus cue capped (defocusEnergy). Labels go in chunks so that only chunk x subsets slices are
// held besides the volume and the one-dimensional subsets' volumes; `gateWanted`: joinOneDimensional's
// (gatesOneDimensional). Returns cost[l * n + p].
CostVolume aggregatedCost(const LightField& grey, const std::vector<double>& disparities, const GuidedFilter& filter,
                          double defocusWeight, double locking, const ViewNoise& noise, bool subsetsApart, bool ceiling,
                          bool gateWanted, StarChoice star);

// Step 5: the fine search (fine_search.cpp).

// How much the views disagree at the map a fine search found: its cost at the minimum per pixel
// (the mean squared difference between the views there) and the median over pixels; empty and 0
// without a fine search.
struct Residual {
  std::vector<float> perPixel;
  double median = 0;
};

// Fine search around a disparity map: the correspondence cost (as correspondenceCost) at
// disparity + k delta per pixel, k in [-steps, steps], each slice aggregated by `filter`, then
// the lowest with a parabola through its neighbours. Slices follow the map, so a window averages
// costs of neighbouring pixels at the same offset from their own disparities: a slanted surface
// stays sharp where fixed labels would step. With `aggregateHalves`, each subset's cost is
// aggregated on its own and the best subset taken per slice afterwards: a window then keeps to one
// subset, where the minimum of per-pixel costs picks whichever subset is lowest by chance at each
// pixel (measured on antinous, fine-search radius 8: BadPix(0.07) 14.2 -> 11.5 %, BadPix(0.03)
// 40.1 -> 28.9 %; issue 6, commit 0915025). Each pixel samples the views at its own disparity, so
// the cost is made a row of one slice at a time by fineCostRow (fine_cost_row.hpp), SIMD across
// the row, rather than from shifted rows as correspondenceCost's.
void refineDisparity(const LightField& grey, const GuidedFilter& filter, float* disparity, double delta, int steps,
                     double locking, const ViewNoise& noise, bool aggregateHalves, bool gateWanted, StarChoice star,
                     float* curvatureOut, float* residualOut);

// The half resolution (half_resolution.cpp).

// A half-resolution plane (each pixel the mean of 2 x 2) at full-resolution pixel (x, y), bilinear.
double sampleHalfResolution(const float* half, int halfWidth, int halfHeight, int x, int y);

// At half the resolution, each pixel the mean of 2 x 2 (an odd last row or column left out).
LightField halfResolution(const LightField& in);
Image halfResolution(const Image& in);

// A half-resolution map at full resolution: bilinear, each disparity doubled (twice the pixels per
// view step).
Image fullResolution(const Image& half, int width, int height);

// The views' brightness offsets (view_offsets.cpp).

// Each view less its brightness offset from the reference view: their difference once the view is
// warped onto the reference by `disparity`, averaged by a guided filter that the map steers
// (`radius`, `epsilon` in squared disparity), so that a brightness that changes smoothly across
// the aperture (a sheen, devignetting left imperfect) cancels while texture stays, and the offsets
// of the two sides of an occlusion edge stay apart. With `slopeCorrected`, the part of each
// difference that the map's error explains (mapError) is taken out first: else, on weak texture,
// the error that a sheen caused in the map passes for part of the offsets and stays. With
// `shrunk`, each offset o is then scaled by o^2 / (o^2 + (kOffsetMapErrorPx g)^2), g the slope
// that a map error moves the view's samples along: kept where it is larger than a map error of
// kOffsetMapErrorPx would make, dropped where it is smaller. With `kept`, each offset is multiplied
// by it (per pixel, in [0, 1]) before it is removed.
void removeViewOffsets(LightField& grey, const Image& disparity, int radius, double epsilon, bool slopeCorrected,
                       bool shrunk, bool fromReference, const std::vector<float>* kept = nullptr);

// Where the view offsets are kept at full resolution (width x height, in [0, 1]): where removing
// them at half resolution left the views agreeing no worse than `before` (view_offsets.cpp).
std::vector<float> offsetsKept(const Residual& before, const std::vector<float>& after, int halfWidth, int halfHeight,
                               int width, int height);

}  // namespace lfcam::edof
