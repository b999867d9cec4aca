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

#include "lfcam/light_field.hpp"
#include "lfcam/result.hpp"

namespace lfcam {

struct DenoiseOptions {
  // The passband, slopes in pixels per view step; equal for a plane (one depth).
  double slopeMin = -2, slopeMax = 2;
  // Standard deviation of the passband's Gaussian roll-off across the segment, cycles per view
  // step: narrower removes more noise, but keeps less of what is not Lambertian (occlusion edges,
  // highlights) and of surfaces near the ends of the range, whose spectrum a few views spread by
  // about 1 / views around their plane. 0.06, chosen among 0.04-0.1 on the textured planes of
  // tests/denoise_test.cpp (9x9 views, range -1:0.5): white noise 2.6x lower, a plane in the range
  // changed by 8-17 % of its texture's rms (0.04: 3.2x and 14-28 %; 0.1: 2.0x and 4-9 %).
  double bandwidth = 0.06;
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
