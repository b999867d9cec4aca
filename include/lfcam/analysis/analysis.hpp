// analysis: the measurements of the paper's section 6 on photographs made by lfcam.
//
// Transfer function: the magnitude of the 2D Fourier transform of the photograph of a point
// source (the pinhole target), normalised to 1 at zero frequency. Cutoff: the smallest radial
// frequency (cycles per pixel, |f| = sqrt(fx^2 + fy^2)) whose disc holds the given share of the
// transfer function's energy (sum of |H|^2), the paper's 75% criterion (Figure 11). SNR: the mean
// of a noise-free standard over the rms difference of a frame from it. Line fits with R^2.
#pragma once

#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

// |FFT| of channel 0 with zero frequency moved to the centre ((w/2, h/2)), divided by |H(0)|.
// With `zeroPadding` P > 1 the photograph is framed by zeros to P times its width and height,
// so the spectrum (P w x P h) samples the photograph's continuous spectrum P times more finely
// than its bins. Usage error for an empty image, one that sums to zero, or P outside 1..64.
// FFTW (single precision).
Result<Image> transferFunction(const Image& photo, int zeroPadding = 1);

// The cutoff of `energyShare` (0..1] of the energy of a transfer function as returned above,
// in cycles per pixel; at most sqrt(0.5) (the corner of the spectrum). The energy within a
// radius is interpolated linearly between the radii of the spectrum's samples, so the cutoff
// varies continuously with the photograph; with a zero-padded spectrum it is not tied to bins.
double cutoffFrequency(const Image& transfer, double energyShare = 0.75);

// Mean of `images` (same size), e.g. the noise-free standard made from many frames.
Result<Image> averageImages(const std::vector<const Image*>& images);

struct SignalToNoise {
  double signal = 0;  // mean of the standard
  double noise = 0;   // rms of frame - standard
  double snr = 0;     // signal / noise (0 when noise is 0)
};
// Over channel 0 of the pixels where `mask` (optional, same size) is positive.
Result<SignalToNoise> signalToNoise(const Image& frame, const Image& standard, const Image* mask = nullptr);

struct LinearFit {
  double slope = 0, intercept = 0;
  double r2 = 0;  // coefficient of determination (1: the points lie on the line)
};
// Least squares y = slope x + intercept; Usage error for fewer than 2 points or constant x.
Result<LinearFit> fitLine(const std::vector<double>& x, const std::vector<double>& y);

// Mean squared gradient (forward differences) of channel 0: a simple focus measure.
double gradientEnergy(const Image& photo);

}  // namespace lfcam
