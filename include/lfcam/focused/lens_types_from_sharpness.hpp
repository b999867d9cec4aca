// The lens types of a focused plenoptic capture told apart without a calibration file: on a
// multi-focus array (Raytrix) the three kinds of microlens are the lattice's three colour classes
// (no two neighbours alike), and each kind is the sharpest of its neighbourhood over its own range
// of virtual depth.
#pragma once

#include <vector>

#include "lfcam/focused/focused_calibration.hpp"

namespace lfcam {

struct LensTypeEvidence {
  // Per micro-image (grid.columns x grid.rows, row-major), 0 where unknown: its sharpness
  // (micro_image_sharpness.hpp) and the virtual depth it sees (focused_depth.hpp).
  std::vector<float> sharpness;
  std::vector<float> virtualDepth;
};

struct LensTypeFinding {
  // One type (every lens alike), or three with their lattice offsets and sharp ranges, which
  // together cover virtual depths 1 to 100 (Raytrix's outer limits).
  std::vector<LensType> lensTypes;
  // How much the colour classes' median relative sharpness (log) differs, averaged over depth:
  // near 0 on a one-focus array.
  double spread = 0;
};

// Each micro-image's sharpness is taken relative to its neighbours' (the log of it less their
// mean log), so that the scene's texture cancels; its colour class's median of that, per band of
// virtual depth (1 px of disparity D / v wide), says which class is sharpest there. The three
// ranges are the order of the classes and the cuts between bands that score best (each kind the
// sharpest over one range). Classes differing by less than `minSpread`, or a capture showing fewer
// than three bands of depth, make one type. Only hexagonal arrays are multi-focus.
// calibration: its grid and reference lens (the offsets are taken from it).
LensTypeFinding lensTypesFromSharpness(const FocusedCalibration& calibration, const LensTypeEvidence& evidence,
                                       double minSpread = 0.15);

}  // namespace lfcam
