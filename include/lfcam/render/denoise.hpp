// denoise: a linear 4D filter in the frequency domain that keeps the surfaces of a range of depths
// and removes what no such surface can produce (Dansereau, Pizarro and Williams 2015, "Linear
// Volumetric Focus for Light Field Cameras"; LFToolbox's LFBuild4DFreqPlane / Hyperfan and
// LFFilt4DFFT).
//
// A Lambertian surface of slope d (light_field.hpp: it appears in view (u, v) displaced by
// (-u d, -v d)) puts all its energy on the plane fu = d fs, fv = d ft of the 4D spectrum (fs, ft in
// cycles per pixel, fu, fv in cycles per view step). Slopes in [slopeMin, slopeMax] fill the
// segment {d (fs, ft)} of the (fu, fv) plane at each spatial frequency: the passband is a Gaussian
// of the distance from (fu, fv) to that segment (a "hyperfan"; a plane when slopeMin == slopeMax),
// the distance taken modulo 1 cycle per view step, since views are samples (aliased surfaces stay
// in the passband). Sensor noise, spread evenly over the spectrum, is mostly outside it.
//
// Borders: each view is mirrored outwards by the farthest a passband slope moves content across
// the aperture. The views are first sheared by the middle slope of the range (each view's spectrum
// times a phase), so that range is centred on slope 0, then mirrored angularly (views 0..n-1, then
// n-1..0): the sequence of views wraps round without a jump, and a mirrored surface keeps a slope
// inside the centred range, so a surface in the passband is kept in the outer views too (exactly at
// the middle slope). The light field's weight is carried over unchanged, not used (a Fourier filter
// cannot normalise per sample).
//
// Memory: about 4 times one channel of the padded light field in complex floats, plus the passband in
// floats; channels are filtered one after the other. FFTW, single precision.
#pragma once

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

struct DenoiseOptions {
  // The passband, slopes in pixels per view step; equal for a plane (one depth).
  double slopeMin = -2, slopeMax = 2;
  // Standard deviation of the passband's Gaussian roll-off across the segment, cycles per view
  // step: narrower removes more noise, but also more of what the views do not share, and a decoded
  // capture's views are not equally sharp (its outer views keep far less of a fine grating than
  // the centre one), so a narrow passband pulls each view towards the views' mean sharpness. 0.11:
  // the narrowest whose centre view keeps its MTF50 within 5 % on the development captures of
  // bench/denoise_bench.cpp (--development: a sine chart at slopes -0.75..0.5, passband -1:0.75;
  // 0.10 loses 5.7 % at -0.75), where the noise falls 1.95-1.98x (0.06: 3.2x, but MTF50 17 % lower).
  double bandwidth = 0.11;
};

// The passband (0..1) at spatial frequency (fs, ft), cycles per pixel, and angular frequency (fu,
// fv), cycles per view step.
double denoisePassband(const DenoiseOptions& options, double fs, double ft, double fu, double fv);

// The range `lfcam denoise` uses without --depth-range: the light field's stated disparity range
// (metadata) when it has one, else [-2, 2], wider than most hand-held captures.
DenoiseOptions defaultDenoiseOptions(const LightField& lightField);

// The filtered light field (same shape, metadata and weight). Usage error for an empty light field,
// slopeMin > slopeMax, non-finite slopes, or a bandwidth outside (0, 0.5].
Result<LightField> denoise(const LightField& lightField, const DenoiseOptions& options);

}  // namespace lfcam
