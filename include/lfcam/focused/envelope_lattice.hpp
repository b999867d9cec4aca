// The lattice of micro-image centres refined by the phase of the image's envelope: each micro-image
// is brightest at its centre (vignetting), so the image's Fourier components at the lattice's
// fundamental frequencies carry the lattice's position in their phase, summed over every pixel.
// Per-lens centres of a focused capture are biased by what each micro-image shows (pixels, and
// coherently over tens of lenses); the phase of thousands of micro-images together is not.
#pragma once

#include <array>

#include "lfcam/core/image.hpp"
#include "lfcam/core/sensor_layout.hpp"

namespace lfcam {

// Micro-image centres at reference + m e1 + n e2 for integers m, n (pixels).
struct MicroImageLattice {
  std::array<double, 2> reference{0, 0}, e1{0, 0}, e2{0, 0};
};

// `start` within a few per cent in pitch and a fraction of the row spacing in position (a per-lens
// fit does that). Each iteration measures the phase of the fundamentals (two on a square lattice,
// three on a hexagonal one) over tiles of a few micro-images and fits the affine map that moves
// the lattice onto them, weighted by the tiles' amplitude.
MicroImageLattice refineLatticeByEnvelope(const Image& image, const MicroImageLattice& start, Packing packing,
                                          int iterations = 3);

}  // namespace lfcam
