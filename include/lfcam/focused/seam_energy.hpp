// How visible the micro-images' lattice is in a photograph rendered from a focused plenoptic image.
// Tiled patches leave an edge along every cell boundary wherever the scene is not at their depth;
// the edges' sign changes from lens to lens with the scene, but their strength repeats with the
// lattice. So the measure is the power of the photograph's gradient magnitude at the first-order
// frequencies of the micro-image lattice (as the photograph's frame scales it); an ideal
// photograph has no more there than at any other frequency. (The photograph's own power at those
// frequencies is mostly the scene's on a textured scene, and misses seams whose sign varies.)
#pragma once

#include "lfcam/core/image.hpp"
#include "lfcam/focused/focused_calibration.hpp"

namespace lfcam {

// That power for `photo` on the frame of pixelsPerLens (photo_frame.hpp): its gradient magnitude
// (mean over channels), less its mean, under a Hann window. Compare a rendering's with the ideal
// photograph's.
double seamEnergy(const Image& photo, const FocusedCalibration& calibration, double pixelsPerLens);

}  // namespace lfcam
