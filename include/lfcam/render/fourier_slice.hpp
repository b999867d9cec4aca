// Fourier slice refocusing (Ng, "Fourier Slice Photography", SIGGRAPH 2005): the photograph
// refocused at slope d is, in the Fourier domain, a 2D slice of the light field's 4D spectrum,
//   E^(fs, ft) = L^(fu = d fs, fv = d ft, fs, ft)        (fu in cycles per view step),
// so after one 4D FFT each photograph costs a 2D slice and an inverse 2D FFT, independent of the
// number of views. The spatial frequencies of the slice fall on the FFT grid; only the angular
// ones do not, and are resampled with a separable Kaiser-Bessel kernel over an angular spectrum
// oversampled by zero-padding, after dividing the views by the kernel's transform (roll-off
// correction).
//
// Differences from refocus.hpp: the image is treated as periodic (content shifted out of one
// border wraps in at the other, within |d| (n - 1) / 2 pixels of the borders), the light field's
// weight is ignored (a Fourier method cannot normalise per pixel), and the result is the mean of
// the views with the views' band-limited (sinc) interpolation instead of bilinear.
// Memory: channels x (oversampling nu) x (oversampling nv) x nt x (ns/2+1) complex floats, about
// 2 oversampling^2 times the light field (8x at the default 2).
#pragma once

#include <complex>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

struct FourierSliceOptions {
  double oversampling = 2.0;  // angular zero-padding factor
  int kernelWidth = 4;        // Kaiser-Bessel taps along each angular axis
};

class FourierRefocuser {
 public:
  // The 4D spectrum of `lightField`. Usage error for an empty light field or bad options.
  static Result<FourierRefocuser> create(const LightField& lightField, const FourierSliceOptions& options = {});

  // The photograph refocused at `slope` (pixels per view step).
  Image refocus(double slope) const;
  std::size_t spectrumBytes() const;

 private:
  LightFieldShape shape_;
  int paddedU_ = 0, paddedV_ = 0;
  double halfU_ = 0, halfV_ = 0;  // centre of the views minus the whole index placed at 0
  int width_ = 4;
  double kaiserBeta_ = 0;
  std::vector<std::vector<std::complex<float>>> spectrum_;  // per channel: [v'][u'][kt][ks]
};

}  // namespace lfcam
