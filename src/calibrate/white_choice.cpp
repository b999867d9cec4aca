// Choosing a capture's white from a database (white_database.hpp): LFToolbox's rule.
#include <cmath>
#include <cstdio>
#include <limits>

#include "lfcam/calibrate/white_database.hpp"

namespace lfcam {

namespace {

std::string steps(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

}  // namespace

Result<WhiteChoice> chooseWhite(const WhiteDatabase& database, const CameraSetting& setting, int width, int height,
                                bool anyCamera, const std::string& capture) {
  const std::string index = database.index.string();
  for (const auto& [value, what] : {std::pair{setting.zoomStep, "zoom"}, std::pair{setting.focusStep, "focus"}})
    if (!value)
      return makeError(ErrorCode::Format, capture + ": its metadata gives no " + what + " step, so no white of " +
                                              index + " can be chosen for it (give one with --white)");
  if (setting.serial.empty() && !anyCamera)
    return makeError(ErrorCode::Usage, capture +
                                           ": its metadata names no camera serial; --any-camera chooses among "
                                           "every camera's whites in " +
                                           index);
  // Candidates: the capture's camera (or any with --any-camera), of its sensor size.
  std::vector<const WhiteRecord*> candidates;
  int ofCamera = 0;
  std::string otherSize;
  for (const WhiteRecord& white : database.whites) {
    if (!anyCamera && white.setting.serial != setting.serial) continue;
    ++ofCamera;
    if (white.width == width && white.height == height)
      candidates.push_back(&white);
    else
      otherSize = sizeText(white.width, white.height);
  }
  if (ofCamera == 0)
    return makeError(ErrorCode::Usage, capture + ": camera " + setting.serial + " has no white in " + index +
                                           " (--any-camera chooses among every camera's whites)");
  if (candidates.empty())
    return makeError(ErrorCode::Format, capture + ": its " + sizeText(width, height) + " pixels match no white of " +
                                            (anyCamera ? std::string("any camera") : "camera " + setting.serial) +
                                            " in " + index + " (" + otherSize + ")");
  // Nearest zoom first, then among those the nearest focus; the first in the index's order on a tie.
  const WhiteRecord* best = nullptr;
  double bestZoom = std::numeric_limits<double>::infinity(), bestFocus = bestZoom;
  for (const WhiteRecord* white : candidates) {
    const double zoom = std::abs(*white->setting.zoomStep - *setting.zoomStep);
    const double focus = std::abs(*white->setting.focusStep - *setting.focusStep);
    if (zoom < bestZoom || (zoom == bestZoom && focus < bestFocus)) best = white, bestZoom = zoom, bestFocus = focus;
  }
  std::string reason =
      best->name + " (zoom step " + steps(*best->setting.zoomStep) + ", focus step " + steps(*best->setting.focusStep) +
      "): of " + std::to_string(candidates.size()) + " whites of " +
      (best->setting.serial == setting.serial ? "camera " + setting.serial
                                              : "camera " + best->setting.serial + " (--any-camera: the capture's is " +
                                                    (setting.serial.empty() ? "unknown" : setting.serial) + ")") +
      ", the nearest in zoom (" + steps(bestZoom) + " steps off), then in focus (" + steps(bestFocus) +
      " steps off) of the capture's zoom step " + steps(*setting.zoomStep) + ", focus step " +
      steps(*setting.focusStep);
  return WhiteChoice{*best, std::move(reason)};
}

Result<WhiteChoice> chooseWhite(const std::filesystem::path& index, const RawImage& raw, bool anyCamera,
                                const std::string& capture) {
  LFCAM_ASSIGN_OR_RETURN(auto database, readWhiteDatabase(index));
  return chooseWhite(database, raw.setting, raw.mosaic.width(), raw.mosaic.height(), anyCamera, capture);
}

}  // namespace lfcam
