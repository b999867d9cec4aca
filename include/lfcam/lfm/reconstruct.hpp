// A volume from one light-field microscope frame: Richardson-Lucy deconvolution through the
// projectors (Broxton et al. 2013, section 5), or the single back-projection users compare it
// with. The frame is rectified (projector.hpp's layout) and dark-subtracted; negative values are
// taken as 0.
#pragma once

#include <cstdint>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/core/volume.hpp"
#include "lfcam/lfm/projector.hpp"

namespace lfcam {

enum class LfmSolver {
  RichardsonLucy,  // x <- x H^T(y / (H x + b)) / H^T 1, from the back-projection
  BackProjection,  // H^T y / H^T 1: the normalised back-projection, no iteration
};

struct LfmReconstructOptions {
  LfmSolver solver = LfmSolver::RichardsonLucy;
  int iterations = 8;     // at most; >= 1
  double tolerance = 0;   // stop once |x_k+1 - x_k| / |x_k| falls below (0: never)
  double background = 0;  // b: light in every pixel that no voxel sends (napari-LF's background_level)
  double tvWeight = 0;    // lambda of RL with total-variation regularisation (Dey et al. 2006), >= 0
};

struct LfmReconstruction {
  Volume volume;
  int iterations = 0;             // run
  std::vector<double> residuals;  // |y - H x| / |y| before each iteration, and after the last
};

// `radiometry`, when given, is R of the model y = R (H x) + b, per pixel (napari-LF's
// premultiplier): a real microscope's lenslet images are not the model's (its pupil, vignetting,
// the camera's gain), and R, the white image over the model's own frame of a uniform volume, says
// by how much; RL then runs on H' = diag(R) H, and pixels where R is 0 are left out.
// Usage error when the frame's (or R's) size is not the projector's lenslets times N, or for
// options out of range. progress(fraction) after each iteration; a cancellation request
// (parallel.hpp) ends the iterations early.
Result<LfmReconstruction> reconstructVolume(const LfmProjector& projector, const Image& frame,
                                            const LfmReconstructOptions& options = {},
                                            const ProgressCallback& progress = {}, const Image* radiometry = nullptr);

// A frame of `volume` as the microscope would record it: the forward projection plus `background`,
// each pixel then a Poisson count of photonsPerUnit times its value, divided back by
// photonsPerUnit (0: no noise). The seed makes it repeatable.
Image simulateLfmFrame(const LfmProjector& projector, const Volume& volume, double background, double photonsPerUnit,
                       std::uint64_t seed);

}  // namespace lfcam
