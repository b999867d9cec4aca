#include "lfcam/focused/focused_capture.hpp"

#include <algorithm>

#include "lfcam/decode/decode.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/raw_io/raw_io.hpp"

namespace lfcam {

namespace {

// The image in [0, 1] of full scale, three channels (or one for a monochrome sensor).
Result<Image> readDemosaiced(const std::filesystem::path& path) {
  LFCAM_ASSIGN_OR_RETURN(Image image, readImage(path));
  if (image.channels() >= 3) {
    if (image.channels() == 3) return image;
    Image rgb(image.width(), image.height(), 3);
    for (int c = 0; c < 3; ++c) std::copy_n(image.plane(c), image.planeSize(), rgb.plane(c));
    return rgb;
  }
  LFCAM_ASSIGN_OR_RETURN(RawImage raw, readRaw(path));
  const float black = float(raw.blackLevel), range = float(std::max(1e-6, raw.whiteLevel - raw.blackLevel));
  for (float& x : raw.mosaic.pixels()) x = std::max(0.0f, (x - black) / range);
  return demosaic(raw.mosaic, raw.colorFilter, DemosaicMethod::MalvarHeCutler);
}

}  // namespace

std::optional<std::filesystem::path> focusedCalibrationBeside(const std::filesystem::path& capture) {
  std::filesystem::path candidate = capture;
  candidate.replace_extension(".xml");
  std::error_code ec;
  if (candidate != capture && std::filesystem::is_regular_file(candidate, ec)) return candidate;
  return std::nullopt;
}

Result<FocusedCapture> readFocusedCapture(const std::filesystem::path& path, const FocusedCaptureOptions& options) {
  FocusedCapture capture;
  if (!options.calibration.empty())
    capture.calibrationPath = options.calibration;
  else if (const auto beside = focusedCalibrationBeside(path))
    capture.calibrationPath = *beside;
  else if (!options.calibrateIfNone)
    return makeError(ErrorCode::Usage,
                     path.string() +
                         ": no focused plenoptic calibration beside it (same name, .xml); name one with "
                         "--focused-calibration, or calibrate it from itself with --focused");
  LFCAM_ASSIGN_OR_RETURN(capture.image, readDemosaiced(path));
  if (!capture.calibrationPath.empty()) {
    LFCAM_ASSIGN_OR_RETURN(capture.calibration, readFocusedCalibration(capture.calibrationPath, capture.image.width(),
                                                                       capture.image.height()));
  }
  std::optional<Image> white;
  if (!options.white.empty()) {
    LFCAM_ASSIGN_OR_RETURN(white, readDemosaiced(options.white));
    if (white->width() != capture.image.width() || white->height() != capture.image.height())
      return makeError(ErrorCode::Usage, options.white.string() + ": the white image is " +
                                             std::to_string(white->width()) + "x" + std::to_string(white->height()) +
                                             ", the capture " + std::to_string(capture.image.width()) + "x" +
                                             std::to_string(capture.image.height()));
  }
  // Without a white image the capture's own vignetting shows its lattice: calibrate before
  // devignetting it.
  if (capture.calibrationPath.empty() && !white) {
    LFCAM_ASSIGN_OR_RETURN(capture.selfCalibration, calibrateFocusedCapture(capture.image, nullptr, {}, path.string()));
    capture.calibration = capture.selfCalibration->calibration;
  }
  if (white) {
    for (int c = 0; c < capture.image.channels(); ++c) {
      const float* w = white->plane(std::min(c, white->channels() - 1));
      const float brightest = *std::max_element(w, w + white->planeSize());
      float* x = capture.image.plane(c);
      for (std::size_t k = 0; k < capture.image.planeSize(); ++k)
        x[k] = w[k] > 0.05f * brightest ? x[k] * brightest / w[k] : 0.0f;
    }
    if (capture.calibrationPath.empty()) {
      LFCAM_ASSIGN_OR_RETURN(capture.selfCalibration,
                             calibrateFocusedCapture(capture.image, &*white, {}, path.string()));
      capture.calibration = capture.selfCalibration->calibration;
    }
  }
  return capture;
}

}  // namespace lfcam
