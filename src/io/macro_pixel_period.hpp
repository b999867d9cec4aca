// Estimating how many pixels a macro-pixel spans in a lenslet image that does not say.
#pragma once

#include <optional>
#include <vector>

#include "lfcam/core/image.hpp"

namespace lfcam::io {

struct MacroPixelPeriod {
  std::optional<int> period;   // when one stands out
  std::vector<int> plausible;  // otherwise the periods that came closest, likeliest first (may be empty)
};

// The period (3 to 256, a divisor of the image's size there leaving at least four macro-pixels) of
// the macro-pixel pattern along x (alongX) or y.
//
// Method: two profiles along the axis, sums over the other axis and the channels: the intensity
// (vignetting under each lens) and the absolute difference of neighbouring pixels (across a
// macro-pixel border the neighbours are views of two lenses, inside two adjacent views of one).
// Each profile's power spectrum is scored for every candidate period k: the mean power in the
// teeth of its comb (the harmonics m n / k, a few bins wide, since a pattern only under part of
// the image, as in a dark microscope frame, spreads its peaks) above the power between the teeth.
// The best k is extended to a multiple when that multiple's own harmonics stand out too, and the
// intensity's is reduced to a divisor when its lenses differ only in brightness (a scene textured
// at the lenses' scale). Accepted when the profiles agree (or one's period divides the other's),
// the comb stands well above the background and explains a fair share of the power.
MacroPixelPeriod estimateMacroPixelPeriod(const Image& image, bool alongX);

}  // namespace lfcam::io
