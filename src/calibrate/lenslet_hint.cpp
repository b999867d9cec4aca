// A starting guess for calibration from metadata: the simulator's camera.json or a Lytro frame
// metadata JSON.
#include <cmath>
#include <functional>

#include <nlohmann/json.hpp>

#include "calibrate/calibrate_internal.hpp"
#include "calibrate/grid_json.hpp"
#include "lfcam/calibrate/calibrate.hpp"

namespace lfcam {

namespace {

// The first object (depth first) for which `match` holds.
const nlohmann::json* findObject(const nlohmann::json& json, const std::function<bool(const nlohmann::json&)>& match,
                                 int depth = 0) {
  if (depth > 32) return nullptr;
  if (json.is_object() && match(json)) return &json;
  if (json.is_object() || json.is_array())
    for (const auto& item : json)
      if (const nlohmann::json* found = findObject(item, match, depth + 1)) return found;
  return nullptr;
}

bool isNumber(const nlohmann::json& json, const char* key) { return json.contains(key) && json.at(key).is_number(); }

}  // namespace

Result<LensletHint> lensletHintFromJson(const nlohmann::json& json, const std::string& where) {
  // camera.json (docs/formats.md): "lattice_px" with pitch_px, rotation_deg, packing, offset_px.
  if (const nlohmann::json* owner =
          findObject(json, [](const nlohmann::json& o) { return o.contains("lattice_px"); })) {
    const nlohmann::json& l = owner->at("lattice_px");
    if (!l.is_object() || !isNumber(l, "pitch_px") || !isNumber(l, "rotation_deg"))
      return makeError(ErrorCode::Format, where + ": lattice_px: expected pitch_px and rotation_deg numbers");
    LensletHint hint;
    hint.pitchPx = l.at("pitch_px").get<double>();
    hint.rotationRad = l.at("rotation_deg").get<double>() * M_PI / 180.0;
    hint.packing = l.value("packing", std::string("square")) == "hexagonal" ? Packing::Hexagonal : Packing::Square;
    if (l.contains("offset_px") && l.at("offset_px").is_array() && l.at("offset_px").size() == 2 &&
        l.at("offset_px")[0].is_number() && l.at("offset_px")[1].is_number())
      hint.offsetPx = {l.at("offset_px")[0].get<double>(), l.at("offset_px")[1].get<double>()};
    return hint;
  }
  // Lytro frame metadata: devices.mla.lensPitch and devices.sensor.pixelPitch (metres),
  // mla.rotation (radians), mla.sensorOffset (metres), mla.tiling ("hexUniformRowMajor").
  const nlohmann::json* devices = findObject(json, [](const nlohmann::json& o) {
    return o.contains("mla") && o.at("mla").is_object() && isNumber(o.at("mla"), "lensPitch") && o.contains("sensor") &&
           o.at("sensor").is_object() && isNumber(o.at("sensor"), "pixelPitch");
  });
  if (!devices)
    return makeError(
        ErrorCode::Format,
        where + ": no lenslet geometry: expected lattice_px (camera.json) or devices.mla (Lytro metadata)");
  const nlohmann::json& mla = devices->at("mla");
  const double pixelPitch = devices->at("sensor").at("pixelPitch").get<double>();
  if (!(pixelPitch > 0)) return makeError(ErrorCode::Format, where + ": devices.sensor.pixelPitch: must be positive");
  LensletHint hint;
  hint.pitchPx = mla.at("lensPitch").get<double>() / pixelPitch;
  hint.rotationRad = isNumber(mla, "rotation") ? mla.at("rotation").get<double>() : 0.0;
  const std::string tiling =
      mla.contains("tiling") && mla.at("tiling").is_string() ? mla.at("tiling").get<std::string>() : "";
  hint.packing = tiling.rfind("hex", 0) == 0 ? Packing::Hexagonal : Packing::Square;
  if (mla.contains("sensorOffset") && mla.at("sensorOffset").is_object() && isNumber(mla.at("sensorOffset"), "x") &&
      isNumber(mla.at("sensorOffset"), "y"))
    hint.offsetPx = {mla.at("sensorOffset").at("x").get<double>() / pixelPitch,
                     mla.at("sensorOffset").at("y").get<double>() / pixelPitch};
  if (!std::isfinite(hint.pitchPx) || !(hint.pitchPx > 0))
    return makeError(ErrorCode::Format, where + ": devices.mla.lensPitch: must be positive");
  return hint;
}

Result<LensletHint> readLensletHint(const std::filesystem::path& path) {
  LFCAM_ASSIGN_OR_RETURN(auto json, calibrate_detail::readJsonFile(path, "a metadata file (.json)"));
  return lensletHintFromJson(json, path.string());
}

}  // namespace lfcam
