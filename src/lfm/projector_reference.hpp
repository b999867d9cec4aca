// The projectors' reference (projector.hpp gives the contract): every voxel's dense PSF placed at
// its lenslet and summed in float64, with no splats, tiles or planes. The tests hold LfmProjector
// to it on random volumes.
#pragma once

#include <vector>

#include "lfcam/lfm/psf.hpp"

namespace lfcam::lfm {

// volume: [z][y][x], lensletsX K x lensletsY K x slices; returns the frame [y][x].
std::vector<double> forwardDirect(const LfmPsfSet& set, const std::vector<double>& volume, int lensletsX,
                                  int lensletsY);
// frame: [y][x], lensletsX N x lensletsY N; returns the volume [z][y][x].
std::vector<double> backwardDirect(const LfmPsfSet& set, const std::vector<double>& frame, int lensletsX,
                                   int lensletsY);

}  // namespace lfcam::lfm
