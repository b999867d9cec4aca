// The scene and camera of `lfcam simulate SCENE` and lfcam.simulate in Python: a scene file whose
// camera the overrides change, or a built-in scene (people, chart, pinhole, white) made for the
// paper's camera with the overrides. One place for both front ends, so they simulate the same.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "lfcam/core/result.hpp"
#include "lfcam/simulate/scene.hpp"

namespace lfcam {

struct CameraOverrides {
  std::optional<double> fNumber, imageFNumber;  // main lens; imageFNumber sets the image-side f-number
  std::optional<double> focusMm;                // focus distance of the main lens
  std::optional<int> size;                      // sensor pixels across and down (the microlens count follows)
  std::optional<double> pixelsPerLens;          // microlens pitch in pixels, keeping the microlens f-number
  bool hexagonal = false, conventional = false;
  std::optional<std::uint64_t> seed;
  std::optional<double> exposure;
  std::optional<bool> noise;
};

// The scene with scene.camera set; a Usage error naming the setting for a value out of range
// (the command line's ranges) or a camera that cannot work.
Result<Scene> simulationScene(const std::string& sceneNameOrFile, const CameraOverrides& overrides);

}  // namespace lfcam
