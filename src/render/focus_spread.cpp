// Focus spread (focus_spread.hpp): a slope per pixel from the disparity map, clamped into the range,
// rendered by the slope-field kernel (slope_field_rows.hpp) without the rays of nearer surfaces
// (occluders.hpp).
#include "lfcam/render/focus_spread.hpp"

#include <cmath>
#include <string>

#include "render/slope_field_rows.hpp"

namespace lfcam {

Status checkFocusSpread(const LightField& lightField, const Image& disparity, double farSlope, double nearSlope) {
  if (disparity.width() != lightField.ns() || disparity.height() != lightField.nt() || disparity.channels() != 1)
    return makeError(ErrorCode::Usage, "focus spread: the disparity map is " + std::to_string(disparity.width()) + "x" +
                                           std::to_string(disparity.height()) + "x" +
                                           std::to_string(disparity.channels()) + ", the views " +
                                           std::to_string(lightField.ns()) + "x" + std::to_string(lightField.nt()) +
                                           " (one channel needed)");
  if (!(std::isfinite(farSlope) && std::isfinite(nearSlope) && nearSlope >= farSlope))
    return makeError(ErrorCode::Usage, "focus spread: the near end of the range (slope " + std::to_string(nearSlope) +
                                           ") lies behind its far end (slope " + std::to_string(farSlope) +
                                           "); slopes grow towards the camera");
  for (float d : disparity.pixels())
    if (!std::isfinite(d)) return makeError(ErrorCode::Usage, "focus spread: the disparity map has non-finite values");
  return {};
}

Result<Image> refocusSpread(const LightField& lightField, const Image& disparity, double farSlope, double nearSlope) {
  LFCAM_TRY(checkFocusSpread(lightField, disparity, farSlope, nearSlope));
  if (lightField.empty()) return Image(lightField.ns(), lightField.nt(), lightField.channels());

  const Occluders occluders(lightField, disparity);
  return refocusFilm(lightField, {.depth = &disparity, .farSlope = farSlope, .nearSlope = nearSlope}, &occluders,
                     nullptr);
}

}  // namespace lfcam
