// Building blocks shared by depth estimation and the all-in-focus photomontage (src/edof/).
// Planes are row-major width x height float arrays.
#pragma once

#include <cstddef>
#include <functional>
#include <type_traits>
#include <vector>

#include "core/box_filter.hpp"
#include "core/target_clones.hpp"
#include "lfcam/core/detail/huge_page_allocator.hpp"
#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"

namespace lfcam::edof {

// A cost volume or a stack of cost slices: tens to hundreds of MiB, read a plane or a pixel's run
// at a time; it comes zeroed, first touched on every thread (huge_page_allocator.hpp). On ordinary
// pages even with LFCAM_HUGE_PAGES=1: huge ones bring these reads in order nothing, and on a
// virtual machine whose balloon takes freed memory back, fresh huge pages fault in several times
// slower than ordinary ones (`lfcam depth` on antinous 0.88x wall with ordinary ones; design.md,
// speed).
struct CostVolumeAllocator : HugePageAllocator<float> {
  template <typename U>
  struct rebind {
    static_assert(std::is_same_v<U, float>);
    using other = CostVolumeAllocator;
  };
  CostVolumeAllocator() noexcept : HugePageAllocator<float>(Pages::Ordinary) {}
};
using CostVolume = std::vector<float, CostVolumeAllocator>;

// Row y of `plane` (ns x nt) shifted by (shiftX, shiftY), sampled bilinearly with positions
// clamped to the plane, as bilinearSample (core/bilinear.hpp) at (x + shiftX, y + shiftY) but a
// row at a time: out[x] for x in [0, ns). `padded` is scratch of ns + 2 pad floats, |shiftX| <= pad - 2.
void sampleShiftedRow(const float* plane, int ns, int nt, int y, double shiftX, double shiftY, int pad, float* padded,
                      float* out);

// Rec. 709 luminance of a linear image (the mean for other channel counts): one channel.
Image luminance(const Image& image);
// The light field of luminance: same views, one channel, weight kept.
LightField luminanceLightField(const LightField& lightField);

// `plane` smoothed in place by a sampled Gaussian of standard deviation `sigma` pixels (taps out
// to 3 sigma, at least one), separable, borders clamped. sigma <= 0 leaves it as it is.
void gaussianBlur(float* plane, int width, int height, double sigma);
// The normalised taps of gaussianBlur's kernel, from -radius to radius.
std::vector<float> gaussianTaps(double sigma);

// Squared 4-neighbour Laplacian of channel 0, borders clamped: a focus energy per pixel.
void squaredLaplacian(const Image& image, float* out);

// A plane's gradient times `scale`, by central differences (the border pixels repeated beyond it).
void centralDifferences(const float* in, int ns, int nt, float scale, float* dx, float* dy);

// Guided filter (He, Sun and Tang 2010) with a grey guide: an edge-preserving smoothing whose
// output is locally a linear function of the guide. Prepared once per guide, applied to many
// inputs (the slices of a cost volume). Thread-safe apply.
class GuidedFilter {
 public:
  GuidedFilter(const float* guide, int width, int height, int radius, double epsilon);
  // Buffers of one apply, kept by the caller across slices (no allocation per slice).
  struct Scratch {
    std::vector<float> a, b, rows, product, meanIn, meanProduct;
    std::vector<const float*> ringA, ringB;  // the rows of a and b a window covers
  };
  // `out` may be `in`: every read of it comes before the first write.
  void apply(const float* in, float* out) const;
  void apply(const float* in, float* out, Scratch& scratch) const;

 private:
  int width_, height_, radius_;
  std::vector<float> guide_, meanGuide_, inverseVariance_;  // 1 / (var + eps)
};

// Confidence-weighted fast global smoother (Min et al. 2014): `values` replaced by
// S(confidence x values) / S(confidence), S the edge-aware weighted least-squares smoother with
// neighbours linked by exp(-|I_p - I_q| / sigma) of the guide (guideChannels planes of
// width x height, L2 over channels) and overall smoothness `lambda`; `iterations` row + column
// passes. Pixels of low confidence take the values of confident ones on their side of an edge.
void globalSmooth(const float* guide, int guideChannels, int width, int height, const float* confidence, float* values,
                  float lambda, float sigma, int iterations);

// Weighted median of n >= 1 (value, weight) pairs, weights >= 0 with a positive total: the smallest
// value whose cumulative weight in ascending order reaches half the total. The reference sorts a
// copy (weighted_median.cpp); the fast one selects by partitions around a pivot, whole vectors at
// a time (weighted_median_select.cpp), reordering both arrays, and reads up to kMedianPadding
// floats past the n-th of each (their values do not matter).
constexpr std::size_t kMedianPadding = 64;  // the widest vector Highway targets, 2048 bits
float weightedMedianSorted(const float* values, const float* weights, std::size_t n, float total);
float weightedMedianSelect(float* values, float* weights, std::size_t n, float total);
// The local slope of a disparity map, px per view step per pixel along x and y, 0 where none
// can be trusted (map_slopes.cpp: measured away from jumps, carried to a jump's side from the
// same surface nearby).
struct MapSlopes {
  std::vector<float> x, y;
};
MapSlopes mapSlopes(const float* disparity, int width, int height);

// Weighted median of a disparity map (width x height of `guide`, an sRGB colour image) over a
// (2 radius + 1)^2 window, each neighbour weighted by its likeness to the pixel in the guide,
// exp(-|I_p - I_q|^2 / (2 sigma^2)): removes isolated mistakes and pulls occlusion edges back onto
// the colour edges (Ma et al. 2013). In colour, not luminance, so that a thin structure of another
// hue but the same brightness as what lies behind it keeps its own disparity. With `slanted`, each
// neighbour's disparity is first carried to the pixel along the map's local slope (beside a jump,
// the slope of the same surface a few pixels away): on a slanted surface a window whose
// like-coloured neighbours lie on one side (a colour edge, a shadow, an occlusion edge) would
// otherwise take their nearer or farther disparity (weighted_median.cpp).
void guidedWeightedMedian(const Image& guide, int radius, float sigma, bool slanted, float* disparity);
// The same, one neighbour at a time, the window sorted: the reference of the fast one.
void guidedWeightedMedianReference(const Image& guide, int radius, float sigma, bool slanted, float* disparity);

// One row y of guidedWeightedMedian (guided_median_row.cpp): what it reads, each array readable
// kMedianPadding floats past its end. weights = table[squared colour distance x steps], at most 1.
struct GuidedMedianInputs {
  std::vector<const float*> planes;  // the guide's
  const float* disparity = nullptr;  // the map before the median
  const float* slopeX = nullptr;     // the map's slopes (mapSlopes), or none: flat
  const float* slopeY = nullptr;
  const float* table = nullptr;  // steps + 1 entries
  int steps = 0, width = 0, height = 0, radius = 0;
};
// `values` and `weights`: room for (2 radius + 1)^2 + kMedianPadding floats.
void guidedMedianRow(const GuidedMedianInputs& inputs, int y, float* values, float* weights, float* out);

// Occlusion edges (occlusion_edges.cpp). Chessboard distance from each pixel to the nearest jump
// (both pixels of a 4-neighbour pair whose disparities differ by more than `jump`), capped at
// cap + 1.
std::vector<int> jumpDistance(const float* disparity, int width, int height, float jump, int cap);
// Pixels within `band` of a jump of the map (width x height of `guide`, an sRGB colour image) move
// to a farther surface when its pixels beyond the band outweigh their own surface's by colour
// likeness: the weighted median of those, with at least one full vote (a thin structure keeps its own);
// with `slanted`, each carried to the pixel along the map's slope where it was (mapSlopes).
// `costAllows(p, from, to, ownVoters)`, when given, may veto a move of pixel p from disparity `from`
// to `to`; `ownVoters` counts the pixels beyond the band on p's own surface, whatever their colour
// (0: a part narrower than the band, which nothing but the cost speaks for).
using ReclaimCheck = std::function<bool(std::size_t p, float from, float to, int ownVoters)>;
void reclaimOcclusionEdges(const Image& guide, int band, bool slanted, float* disparity,
                           const ReclaimCheck& costAllows = {});

// Semi-global optimisation (Hirschmueller 2008) of a cost volume stored pixel-major:
// cost[(y * width + x) * labels + l]. Sums, over 8 path directions, the path costs
//   Lr(p, l) = C(p, l) + min(Lr(p-r, l), Lr(p-r, l+-1) + P1, min_k Lr(p-r, k) + P2(p)) - min_k Lr(p-r, k)
// with P2(p) = max(P1, P2 / (1 + |I(p) - I(p-r)| / edgeScale)) lowered across edges of `guide`.
// Returns the summed volume, same layout.
CostVolume semiGlobalMatching(const CostVolume& cost, int width, int height, int labels, const float* guide, float p1,
                              float p2, float edgeScale);

// Per pixel: argmin over labels with a parabola through its neighbours: a continuous label in
// [0, labels - 1].
void winnerTakesAll(const CostVolume& volume, int width, int height, int labels, float* label);

// Laplacian-pyramid (multi-band) blending of Burt and Adelson 1983, accumulated one source at a
// time so that no stack needs to be held: add(image, weight) for every source whose weights
// (summing to 1 over sources at each pixel) are not all zero, then result().
class PyramidBlender {
 public:
  PyramidBlender(int width, int height, int channels, int levels);
  void add(const Image& image, const float* weight);
  Image result() const;

 private:
  struct Level {
    int width, height;
    std::vector<float> data;  // channels planes
  };
  int channels_;
  std::vector<Level> accumulator_;
};

}  // namespace lfcam::edof
