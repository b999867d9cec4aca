#include "lfcam/simulate/simulate_setup.hpp"

#include <filesystem>

#include "lfcam/simulate/camera_model.hpp"

namespace lfcam {

namespace {

Status checkRange(const std::optional<double>& value, double min, double max, const std::string& name) {
  if (value && !(*value >= min && *value <= max))
    return makeError(ErrorCode::Usage, name + ": " + std::to_string(*value) + " is outside [" + std::to_string(min) +
                                           ", " + std::to_string(max) + "]");
  return {};
}

}  // namespace

Result<Scene> simulationScene(const std::string& sceneNameOrFile, const CameraOverrides& o) {
  LFCAM_TRY(checkRange(o.fNumber, 0.5, 1000, "f-number"));
  LFCAM_TRY(checkRange(o.imageFNumber, 0.5, 1000, "image f-number"));
  LFCAM_TRY(checkRange(o.focusMm, 1e-9, 1e300, "focus distance (mm)"));
  LFCAM_TRY(checkRange(o.size ? std::optional<double>(*o.size) : std::nullopt, 8, 20000, "size"));
  LFCAM_TRY(checkRange(o.pixelsPerLens, 1, 1000, "pixels per lens"));
  LFCAM_TRY(checkRange(o.exposure, 0, 1e300, "exposure"));
  if (o.fNumber && o.imageFNumber)
    return makeError(ErrorCode::Usage, "simulate: give the f-number or the image-side f-number, not both");
  const bool builtin = isBuiltinSceneName(sceneNameOrFile) && !std::filesystem::exists(sceneNameOrFile);
  CameraModel camera = CameraModel::paperPrototype();
  Scene scene;
  if (!builtin) {
    LFCAM_ASSIGN_OR_RETURN(scene, loadScene(sceneNameOrFile));
    camera = scene.camera;
  }
  if (o.focusMm) camera.mainLens.focusDistanceMm = *o.focusMm;
  if (o.fNumber) camera.mainLens.fNumber = *o.fNumber;
  if (o.size) camera.sensor.width = camera.sensor.height = *o.size;
  if (o.conventional) camera.microlenses.reset();
  if (camera.microlenses) {
    if (o.pixelsPerLens) {
      const double fNumber = camera.microlenses->fNumber();
      camera.microlenses->pitchMm = *o.pixelsPerLens * camera.sensor.pixelPitchMm;
      camera.microlenses->focalLengthMm = fNumber * camera.microlenses->pitchMm;
    }
    if (o.hexagonal) camera.microlenses->packing = Packing::Hexagonal;
    if (o.size) camera.microlenses->columns = camera.microlenses->rows = 0;
  }
  if (o.seed) camera.sensor.seed = *o.seed;
  if (o.exposure) camera.sensor.exposure = *o.exposure;
  if (o.noise) camera.sensor.noise = *o.noise;
  LFCAM_TRY(camera.validate("--focus-mm/--f-number/--size"));
  if (o.imageFNumber) camera.mainLens.setImageSideFNumber(*o.imageFNumber);
  if (builtin) {
    LFCAM_ASSIGN_OR_RETURN(scene, builtinScene(sceneNameOrFile, camera));
  }
  scene.camera = camera;
  return scene;
}

}  // namespace lfcam
