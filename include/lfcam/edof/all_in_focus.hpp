// Extended depth of field by digital photomontage (paper, section 5.2 and Figure 15, after
// Agarwala et al. 2004): a photograph with everything in focus, composed from photographs
// refocused (full aperture, Equation 6) at many depths, so it keeps their light gathering: each
// pixel is the mean of nu x nv rays instead of the one ray of a sub-aperture image of the same
// depth of field, and is about sqrt(nu nv) times less noisy (Figure 15).
//
// How allInFocus works (src/edof/all_in_focus.cpp):
//  1. Focal stack: slopes evenly spaced over [disparityMin, disparityMax] (options; else the
//     depth map's range; else the metadata; else [-2, 2]), one step 1 / (max(nu, nv) - 1) by
//     default, so that a surface halfway between two slices is blurred over at most
//     (n - 1) step / 2 = 1/2 pixel.
//  2. A slice label per pixel. Given a depth map (`disparity`), of the slice nearest the pixel's
//     disparity and its two neighbours, the sharpest (the focus measure below, unregularised).
//     Otherwise a focus measure per slice, the squared Laplacian of its luminance
//     averaged over a (2 r + 1)^2 window, regularised across pixels by semi-global optimisation
//     whose jump penalty drops across edges of the centre view (edge-aware), then the sharpest.
//  3. Compositing: Laplacian-pyramid (multi-band) blending of the slices under their label masks
//     (Burt and Adelson 1983), which hides the seams between labels: each band is blended over a
//     width matched to its wavelength.
// Cost: one refocus per slice, as focal stacks (refocus.hpp), the slices kept from the focus
// measure to the blend while they fit in 256 MiB, and a pyramid per slice used: about 55 refocus
// times for HCI antinous (9x9 views of 512x512, 48 slices) given its depth map
// (bench/depth_bench.cpp, BM_AllInFocus).
#pragma once

#include <optional>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

struct AllInFocusOptions {
  // A disparity map of the aperture centre (ns x nt, 1 channel; depth.hpp), e.g. from
  // estimateDepth: replaces the focus measure. Non-finite pixels take the middle slice.
  const Image* disparity = nullptr;
  std::optional<double> disparityMin, disparityMax;
  double sliceStep = 0;     // slope between slices; 0: 1 / (max(nu, nv) - 1)
  int maxSlices = 64;       // the step grows if the range would need more
  int focusRadius = 3;      // focus measure window
  double smoothness = 1.0;  // label regularisation; 0: the sharpest slice per pixel
  int levels = 0;           // pyramid levels; 0: automatic (about log2(size) - 3)
};

struct AllInFocus {
  Image photo;                 // ns x nt, the light field's channels
  Image slope;                 // ns x nt, 1 channel: the slope of the slice chosen per pixel
  std::vector<double> slopes;  // the focal stack's slopes, ascending
};

// Usage error for an empty light field, a disparity map of the wrong size, or an empty range.
Result<AllInFocus> allInFocus(const LightField& lightField, const AllInFocusOptions& options = {});

}  // namespace lfcam
