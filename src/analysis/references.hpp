// The oracles the fast analysis kernels are tested against (not public).
#pragma once

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

// transferFunction (analysis.hpp) by a direct float64 DFT (O(w^2 h^2)).
Result<Image> transferFunctionReference(const Image& photo, int zeroPadding = 1);

}  // namespace lfcam
