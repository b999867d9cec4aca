// The true lenslet grid of a simulated camera, in LensletGrid's convention: the ground truth
// that calibration and decoding are tested against.
#pragma once

#include "lfcam/camera_model.hpp"
#include "lfcam/lenslet_grid.hpp"

namespace lfcam {

// Microlens (i, j) of the grid is the simulator's microlens (i, j) (camera_model.hpp), so
// centre(i, j) == camera.microlensImageCentrePx(i, j); columns x rows is microlensCounts() (all
// of the simulator's microlenses, even those whose image is partly off the sensor), hexParity 0
// (the simulator shifts odd rows). The sensor image is upside down: idealLightField's (s, t) is
// (columns - 1 - i, rows - 1 - j). fit is left empty. Requires a microlens array.
LensletGrid gridFromCamera(const CameraModel& camera);

}  // namespace lfcam
