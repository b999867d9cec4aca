// The JSON form of a Raytrix calibration: the XML's elements as keys (docs/formats.md).
#include <nlohmann/json.hpp>

#include "core/json_reader.hpp"
#include "focused/ray_calib_document.hpp"

namespace lfcam {

namespace {

using focused_detail::RayCalibDocument;
using json_reader::JsonObject;
using nlohmann::json;

constexpr double kLarge = 1e6;

// {"x": ..., "y": ...}
Status readPair(const JsonObject& parent, const char* key, std::array<double, 2>& out) {
  parent.markSeen(key);
  if (!parent.has(key)) return {};
  JsonObject o(parent.at(key), parent.where(), parent.keyPath(key));
  LFCAM_TRY(o.requireObject());
  if (!o.has("x") || !o.has("y")) return o.fail(parent.keyPath(key), "expected {\"x\": ..., \"y\": ...}");
  LFCAM_TRY(o.number("x", out[0], -kLarge, kLarge));
  LFCAM_TRY(o.number("y", out[1], -kLarge, kLarge));
  return o.noUnknownKeys();
}

json pairJson(const std::array<double, 2>& value) { return {{"x", value[0]}, {"y", value[1]}}; }

}  // namespace

Result<FocusedCalibration> parseFocusedCalibrationJson(const std::string& text, const std::string& where, int width,
                                                       int height) {
  json document;
  try {
    document = json::parse(text);
  } catch (const json::exception& e) {
    std::string message = e.what();
    const auto at = message.find("parse error");
    if (at != std::string::npos) message = message.substr(at);
    return makeError(ErrorCode::Format, where + ": not valid JSON: " + message);
  }
  JsonObject root(document, where, "");
  LFCAM_TRY(root.requireObject());
  if (!root.has("offset") || !root.has("diameter"))
    return makeError(ErrorCode::Format,
                     where + ": not a focused plenoptic calibration (no \"offset\" and \"diameter\")");
  RayCalibDocument d;
  LFCAM_TRY(readPair(root, "offset", d.offset));
  LFCAM_TRY(root.number("diameter", d.diameter, 0, kLarge, true));
  LFCAM_TRY(root.number("rotation", d.rotation, -kLarge, kLarge));
  LFCAM_TRY(root.number("lens_border", d.lensBorder, 0, kLarge));
  LFCAM_TRY(root.optionalNumber("tcp", d.tcp, 0, kLarge, true));
  LFCAM_TRY(readPair(root, "lens_base_x", d.lensBaseX));
  LFCAM_TRY(readPair(root, "lens_base_y", d.lensBaseY));
  if (root.has("sub_grid_base")) {
    std::array<double, 2> base{};
    LFCAM_TRY(readPair(root, "sub_grid_base", base));
    d.subGridBase = base;
  }
  root.markSeen("sub_grid_base");
  std::string orientation = "upright";
  LFCAM_TRY(root.string("micro_images", orientation));
  const auto parsed = focused_detail::orientationFromName(orientation);
  if (!parsed) return root.fail("micro_images", "expected \"upright\" or \"inverted\", got \"" + orientation + "\"");
  d.orientation = *parsed;
  root.markSeen("lens_types");
  if (root.has("lens_types")) {
    const json& types = root.at("lens_types");
    if (!types.is_array()) return root.fail("lens_types", "expected an array");
    for (std::size_t t = 0; t < types.size(); ++t) {
      const std::string path = "lens_types[" + std::to_string(t) + "]";
      JsonObject o(types[t], where, path);
      LFCAM_TRY(o.requireObject());
      LensType type;
      LFCAM_TRY(readPair(o, "offset", type.offset));
      o.markSeen("depth_range");
      if (!o.has("depth_range")) return o.fail(path + ".depth_range", "missing");
      JsonObject range(o.at("depth_range"), where, path + ".depth_range");
      LFCAM_TRY(range.requireObject());
      LFCAM_TRY(range.number("min", type.minVirtualDepth, 0, kLarge, true));
      LFCAM_TRY(range.number("max", type.maxVirtualDepth, 0, kLarge, true));
      LFCAM_TRY(range.noUnknownKeys());
      LFCAM_TRY(o.noUnknownKeys());
      d.lensTypes.push_back(type);
    }
  }
  root.markSeen("optics");
  if (root.has("optics")) {
    JsonObject o(root.at("optics"), where, "optics");
    LFCAM_TRY(o.requireObject());
    FocusedOptics optics;
    LFCAM_TRY(o.number("main_focal_length_mm", optics.mainFocalLengthMm, 0, kLarge, true));
    LFCAM_TRY(o.number("main_to_microlenses_mm", optics.mainLensToMicrolensesMm, 0, kLarge, true));
    LFCAM_TRY(o.number("microlenses_to_sensor_mm", optics.microlensesToSensorMm, 0, kLarge, true));
    LFCAM_TRY(o.noUnknownKeys());
    d.optics = optics;
  }
  LFCAM_TRY(root.noUnknownKeys());
  return focused_detail::calibrationFromDocument(d, where, width, height);
}

std::string focusedCalibrationJson(const FocusedCalibration& calibration) {
  const RayCalibDocument d = focused_detail::documentFromCalibration(calibration);
  json out;
  out["offset"] = pairJson(d.offset);
  out["diameter"] = d.diameter;
  out["rotation"] = d.rotation;
  out["lens_border"] = d.lensBorder;
  if (d.tcp) out["tcp"] = *d.tcp;
  out["lens_base_x"] = pairJson(d.lensBaseX);
  out["lens_base_y"] = pairJson(d.lensBaseY);
  if (d.subGridBase) out["sub_grid_base"] = pairJson(*d.subGridBase);
  out["lens_types"] = json::array();
  for (const LensType& type : d.lensTypes)
    out["lens_types"].push_back({{"offset", pairJson(type.offset)},
                                 {"depth_range", {{"min", type.minVirtualDepth}, {"max", type.maxVirtualDepth}}}});
  out["micro_images"] = focused_detail::orientationName(d.orientation);
  if (d.optics)
    out["optics"] = {{"main_focal_length_mm", d.optics->mainFocalLengthMm},
                     {"main_to_microlenses_mm", d.optics->mainLensToMicrolensesMm},
                     {"microlenses_to_sensor_mm", d.optics->microlensesToSensorMm}};
  return out.dump(2) + "\n";
}

}  // namespace lfcam
