// The power spectrum of a sequence, for finding what repeats in it.
#pragma once

#include <span>
#include <vector>

namespace lfcam {

// |DFT|^2 of the sequence with its mean removed, at frequencies 0 .. n / 2 (cycles per sequence):
// n / 2 + 1 values, the first 0. Through FFTW (single precision), in O(n log n).
std::vector<double> powerSpectrum(std::span<const double> sequence);
// The same by the plain sum over the sequence for every frequency, in double precision: O(n^2),
// what the fast one is tested against.
std::vector<double> powerSpectrumReference(std::span<const double> sequence);

}  // namespace lfcam
