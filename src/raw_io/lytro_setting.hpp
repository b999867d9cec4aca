// The camera and lens setting (raw_image.hpp's CameraSetting) in Lytro metadata, in each layout the
// cameras wrote (examples in ../shared/data/lytro-metadata/):
//   "lytro-frame": a frame's metadata, devices.lens.{zoomStep, focusStep},
//     devices.shutter.frameExposureDuration, camera.{model, firmware}; the serial in the frame's
//     private metadata, camera.serialNumber (F01 raws, F01 and Illum white images' .TXT, which
//     wrap both in master.picture.frameArray[0].frame);
//   "lytro-public": an Illum picture's public metadata, {zoomStep, focusStep}, camera.serialNumber,
//     cameraModel at the top.
#pragma once

#include <nlohmann/json.hpp>

#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam {

// `document`: any of the above; `privateMetadata`: the frame's private metadata section when it is
// apart (a container's privateMetadataRef), else nullptr. Fields not found stay empty.
CameraSetting lytroCameraSetting(const nlohmann::json& document, const nlohmann::json* privateMetadata);

}  // namespace lfcam
