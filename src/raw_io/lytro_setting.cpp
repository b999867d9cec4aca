// Camera setting in Lytro metadata (lytro_setting.hpp).
#include "raw_io/lytro_setting.hpp"

#include <cmath>

#include "raw_io/lytro_metadata.hpp"

namespace lfcam {

namespace {

using nlohmann::json;

const json* at(const json& document, const char* pointer) {
  const json::json_pointer p(pointer);
  return document.contains(p) ? &document.at(p) : nullptr;
}

std::optional<double> number(const json* value) {
  if (!value || !value->is_number() || !std::isfinite(value->get<double>())) return std::nullopt;
  return value->get<double>();
}

std::string text(const json* value) { return value && value->is_string() ? value->get<std::string>() : ""; }

}  // namespace

CameraSetting lytroCameraSetting(const json& document, const json* privateMetadata) {
  CameraSetting setting;
  if (!document.is_object()) return setting;
  if (const json* frame = findLytroFrameMetadata(document)) {
    setting.zoomStep = number(at(*frame, "/devices/lens/zoomStep"));
    setting.focusStep = number(at(*frame, "/devices/lens/focusStep"));
    setting.exposureS = number(at(*frame, "/devices/shutter/frameExposureDuration"));
    setting.model = text(at(*frame, "/camera/model"));
    setting.firmware = text(at(*frame, "/camera/firmware"));
    if (setting.zoomStep || setting.focusStep) setting.metadataKeys = "lytro-frame";
  }
  if (!setting.zoomStep && !setting.focusStep) {
    setting.zoomStep = number(at(document, "/zoomStep"));
    setting.focusStep = number(at(document, "/focusStep"));
    if (setting.model.empty()) setting.model = text(at(document, "/cameraModel"));
    if (setting.zoomStep || setting.focusStep) setting.metadataKeys = "lytro-public";
  }
  // The serial: apart, inside a white image's wrapper, or in the public metadata (which wins there:
  // an Illum picture's wrapped frame may name the desktop software's simulator).
  const json* publicSerial = at(document, "/camera/serialNumber");
  for (const json* serial : {setting.metadataKeys == "lytro-public" ? publicSerial : nullptr,
                             privateMetadata ? at(*privateMetadata, "/camera/serialNumber") : nullptr,
                             at(document, "/master/picture/frameArray/0/frame/privateMetadata/camera/serialNumber"),
                             at(document, "/privateMetadata/camera/serialNumber"), publicSerial})
    if (setting.serial.empty()) setting.serial = text(serial);
  return setting;
}

}  // namespace lfcam
