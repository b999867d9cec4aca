// The small plenoptic camera the tests of the simulator's `people` scene (scene.hpp) look through:
// the paper's prototype shrunk to 9 sensor pixels under each of 80x80 microlenses (9x9 views of
// 80x80; or another count) at f/4 like the main lens's image side, focused at 5 m so that the scene's cards (0.8 to
// 2 times the focus distance) lie within the sharp refocusing range (disparities of -1 to +0.5
// pixel per view; at 457 mm they would span -15 to +8).
#pragma once

#include "lfcam/simulate/camera_model.hpp"

namespace lfcam::test {

inline CameraModel peopleCamera(int microlenses = 80) {
  CameraModel camera = CameraModel::paperPrototype(9 * microlenses, 9 * microlenses);
  camera.microlenses->pitchMm = 9 * camera.sensor.pixelPitchMm;
  camera.microlenses->focalLengthMm = 4 * camera.microlenses->pitchMm;
  camera.mainLens.focusDistanceMm = 5000;
  return camera;
}

}  // namespace lfcam::test
