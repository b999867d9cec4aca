// The frame the denoise filter (denoise.hpp) works in, shared by the FFT path and its float64
// reference: each view mirrored outwards by `margin` pixels (one more at the far end where needed,
// so that both sizes are odd and no frequency bin is its own mirror), and the views mirrored
// angularly to twice their count.
#pragma once

#include "lfcam/core/light_field.hpp"
#include "lfcam/render/denoise.hpp"

namespace lfcam::denoise_detail {

struct DenoisePadding {
  int margin = 0;      // pixels mirrored before the first column and row
  int ns = 0, nt = 0;  // padded view size, odd
  int nu = 0, nv = 0;  // twice the view counts: views 0..n-1, then n-1..0
  double shear = 0;    // the passband's middle slope, removed before the angular transform
};
DenoisePadding paddingFor(const LightFieldShape& shape, const DenoiseOptions& options);

// Index `index` of a row of `size` samples mirrored about its ends (-1 -> 0, size -> size - 1).
int mirror(int index, int size);
// Frequency of DFT bin k of `size`, in cycles per sample, in (-1/2, 1/2].
double frequency(int k, int size);
// The passband in the sheared frame: the slopes relative to the shear.
DenoiseOptions shearedPassband(const DenoiseOptions& options, const DenoisePadding& padding);
// What the filter applies in the sheared, angularly mirrored frame: mirroring u and v maps a surface's
// (fu, fv) = d (fs, ft) to (+-d fs, +-d ft), so the segment along (fs, -ft) passes too.
double mirroredPassband(const DenoiseOptions& sheared, double fs, double ft, double fu, double fv);

}  // namespace lfcam::denoise_detail
