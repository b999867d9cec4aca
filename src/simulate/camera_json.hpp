// The camera model as JSON (not public): the "camera" object of a scene file and camera.json.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "lfcam/core/result.hpp"
#include "lfcam/simulate/camera_model.hpp"

namespace lfcam {

// Reads the "camera" object of a scene file over `base` (unset keys keep base's values). `where`
// (a file name) starts every error message, followed by the key path.
Result<CameraModel> cameraFromJson(const nlohmann::json& json, const CameraModel& base, const std::string& where);
// The whole model as written to camera.json (docs/formats.md), including the derived lattice.
nlohmann::json cameraToJson(const CameraModel& camera);

}  // namespace lfcam
