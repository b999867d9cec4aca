// The true lenslet grid of a simulated camera, in LensletGrid's convention: the ground truth
// that calibration and decoding are tested against.
#pragma once

#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/simulate/camera_model.hpp"

namespace lfcam {

// The grid of the raw as the camera stores it (turned by 180 degrees, camera_model.hpp): its
// microlens (i, j) is the simulator's microlens (columns - 1 - i, rows - 1 - j), so centre(i, j)
// == camera.microlensImageCentrePx(columns - 1 - i, rows - 1 - j), and it is idealLightField's
// sample (s, t) = (i, j). columns x rows is microlensCounts() (all of the simulator's microlenses,
// even those whose image is partly off the sensor); hexParity is rows & 1 (the simulator shifts
// its odd rows, which the turn makes the unshifted ones). fit is left empty. Requires a microlens
// array.
LensletGrid gridFromCamera(const CameraModel& camera);

}  // namespace lfcam
