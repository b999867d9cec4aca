// Estimating how many pixels a macro-pixel spans in a lenslet image that does not say.
#pragma once

#include <optional>

#include "lfcam/image.hpp"

namespace lfcam::io {

// The period (>= 2) of the macro-pixel pattern along x (alongX) or y, among the divisors of the
// image's size there, or nothing when no period stands out.
//
// Method: the absolute differences between neighbouring pixels form a profile along the axis.
// Across a macro-pixel border the neighbours are the last and first views of adjacent lenses;
// inside, adjacent views of one lens: the two kinds differ in their statistics (vignetting,
// parallax), so the profile is periodic with the period of the macro-pixels. Each candidate
// period folds the profile into phases; the analysis-of-variance F ratio (variance between
// phases over variance within them) is largest at the true period, and halves at its multiples.
std::optional<int> estimateMacroPixelPeriod(const Image& image, bool alongX);

}  // namespace lfcam::io
