// Refocusing on a finer grid than the microlenses (LFToolbox's UpsampRate): the photograph of
// refocus.hpp rendered K times wider and taller by placing each view's samples where the shift
// of Equation 6 puts them, instead of resampling every view at the output pixels.
//
// Sample (i, j) of view (u, v) lands, at slope d, on the refocused image at (i + u d, j + v d)
// (view pixels, light_field.hpp's convention), that is at fine pixel
//   X = (i + u d + 0.5) K - 0.5,   Y = (j + v d + 0.5) K - 0.5,
// where it is splatted with a tent kernel: fine pixel (x, y) gains w L with
//   w = W(u, v, i, j) t(x - X, hx) cx(u, x mod K) t(y - Y, hy) cy(v, y mod K),
//   t(e, h) = max(0, 1 - |e| / h)
// (W the light field's weight, 1 where it has none), and the sums are divided by the sum of w, so
// every pixel is the weighted mean of the samples that landed near it; a pixel none reached is 0.
// Per axis, h is twice the farthest any fine pixel lies from the nearest landing sample of any
// view, within [3/8, 1/2] of a view pixel (K = 1: one pixel, bilinear interpolation): narrow where
// the views interleave, so that a pixel takes the samples on it rather than its neighbours' too,
// yet wide enough to reach a sample midway between two fine pixels, so that no view's light is
// lost; half a view pixel where the samples pile up. c tilts the weights of the views that a fine
// phase draws on, c = max(0, 1 + a u) with a such that their mean u is 0: every phase sees an
// aperture centred as the plain refocus's does, so what is out of focus falls where the plain
// refocus puts it at every phase, instead of shifting from one fine pixel to the next (the
// blocks of an enlargement).
//
// Away from the plane of the microlenses the views see the refocused plane at different
// sub-pixel phases (u d is not a whole number of pixels), so the samples interleave and the fine
// grid holds detail beyond the microlenses' Nyquist limit. On the plane (d = 0, or any slope where
// every u d is a whole number) they pile up: the result is the plain refocus with each pixel
// repeated K x K times, no detail invented. K = 1 is refocus (the tent of half-width 1 is its
// bilinear interpolation).
//
// refocusUpsampled is the fast kernel (float32, views outer, threaded over blocks of fine rows),
// tested against a plain float64 splat of every sample (src/render/references.hpp).
#pragma once

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

constexpr int kMaxUpsampleFactor = 4;

// The photograph focused at `slope` (pixels per view step) on a grid `factor` times finer:
// (factor ns) x (factor nt) pixels, the light field's channels. Usage error for a factor outside
// 1..kMaxUpsampleFactor.
Result<Image> refocusUpsampled(const LightField& lightField, double slope, int factor);

}  // namespace lfcam
