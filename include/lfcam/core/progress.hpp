// Progress reporting from long library operations, without the library knowing about terminals.
#pragma once

#include <functional>

namespace lfcam {

// Called with the fraction of the work done, in [0, 1], from the calling thread only.
using ProgressCallback = std::function<void(double fraction)>;

}  // namespace lfcam
