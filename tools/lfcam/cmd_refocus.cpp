// lfcam refocus INPUT (--slope D | --alpha A | --focus-at X,Y) -o OUT: a photograph focused after
// the fact (Equation 6), through any synthetic aperture and lens plane (Equation 5); or focused on
// a tilted plane (tilted_focus.hpp): --focus-plane X1,Y1:X2,Y2:X3,Y3, or --tilt T [--tilt-direction
// DEG] about the --slope or --alpha at the image centre; --upsample K renders it on a grid K times
// finer (upsampled_refocus.hpp); --focus-range NEAR:FAR keeps everything between two depths in
// focus (focus_spread.hpp), on the disparity map of --depth or one estimated on the way.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "commands.hpp"
#include "image_output.hpp"
#include "lfcam/depth.hpp"
#include "lfcam/focal_stack.hpp"
#include "lfcam/focus_spread.hpp"
#include "lfcam/image_io.hpp"
#include "lfcam/synthetic_camera.hpp"
#include "lfcam/tilted_focus.hpp"
#include "lfcam/upsampled_refocus.hpp"
#include "render_cli.hpp"

namespace lfcam::cli {

namespace {

// "NEAR:FAR" in slopes (pixels per view step, the near end the larger), or "NEARmm:FARmm" in
// millimetres from the main lens where the optics are known -> {far slope, near slope}.
Result<std::pair<double, double>> parseFocusRange(const std::string& text, const LightField& lightField,
                                                  const std::string& input) {
  const auto colon = text.find(':');
  auto bad = [&] {
    return makeError(ErrorCode::Usage,
                     "--focus-range: expected NEAR:FAR as slopes or as distances NEARmm:FARmm, got '" + text + "'");
  };
  if (colon == std::string::npos) return bad();
  std::string ends[2] = {text.substr(0, colon), text.substr(colon + 1)};
  bool millimetres[2] = {false, false};
  double values[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    if (ends[i].size() > 2 && ends[i].compare(ends[i].size() - 2, 2, "mm") == 0) {
      millimetres[i] = true;
      ends[i].resize(ends[i].size() - 2);
    }
    char end = 0;
    if (std::sscanf(ends[i].c_str(), "%lf%c", &values[i], &end) != 1 || !std::isfinite(values[i])) return bad();
  }
  if (millimetres[0] != millimetres[1]) return bad();
  if (!millimetres[0]) {
    if (values[0] < values[1])
      return makeError(ErrorCode::Usage, "--focus-range: the near end (slope " + ends[0] +
                                             ") lies behind the far end (slope " + ends[1] +
                                             "); slopes grow towards the camera");
    return std::pair{values[1], values[0]};
  }
  if (!(values[0] > 0) || values[0] > values[1])
    return makeError(ErrorCode::Usage, "--focus-range: the near distance (" + ends[0] +
                                           " mm) must be positive and no farther than the far one (" + ends[1] +
                                           " mm)");
  if (!lightField.metadata.optics)
    return makeError(ErrorCode::Usage, input +
                                           ": --focus-range in mm needs the optics (focal length), which this "
                                           "light field does not record; give the range in slopes");
  const auto nearSlope = disparityFromDistance(*lightField.metadata.optics, values[0]);
  const auto farSlope = disparityFromDistance(*lightField.metadata.optics, values[1]);
  if (!nearSlope || !farSlope)
    return makeError(ErrorCode::Usage, input + ": --focus-range in mm needs a focal length, and distances beyond it");
  return std::pair{*farSlope, *nearSlope};
}

}  // namespace

void addRefocusCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::optional<double> slope, alpha;
    std::string focusAt, focusPlane;
    std::optional<double> tilt;
    double tiltDirection = 0;
    int upsample = 1;
    std::string focusRange, depthMap;
    CameraOptions camera;
    std::string output, depth;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("refocus", "refocus a light field (Equations 5 and 6)");
  addInputOptions(*command, options->input);
  auto* slope = command->add_option("--slope", options->slope,
                                    "disparity brought into focus, pixels per view step (HCI convention)");
  auto* alpha =
      command
          ->add_option("--alpha", options->alpha, "relative depth of the synthetic film plane (needs optics metadata)")
          ->check(CLI::PositiveNumber);
  auto* focusAt = command->add_option("--focus-at", options->focusAt,
                                      "focus where image point X,Y (pixels) is sharpest; prints the slope chosen");
  auto* focusPlane = command->add_option(
      "--focus-plane", options->focusPlane,
      "focus on the tilted plane through three image points X1,Y1:X2,Y2:X3,Y3 (pixels), each at its sharpest");
  auto* tilt = command->add_option("--tilt", options->tilt,
                                   "tilt the plane of focus: the change of slope over one image width, about the "
                                   "--slope or --alpha at the image centre");
  command
      ->add_option("--tilt-direction", options->tiltDirection,
                   "direction in which the slope grows, degrees (0: to the right, 90: down; default 0)")
      ->needs(tilt);
  command->add_option("--upsample", options->upsample,
                      "render on a grid K times finer (K = 2 or 3; 1: off, the default), each view's samples "
                      "placed where they land: detail finer than the microlenses away from their plane");
  auto* focusRange = command->add_option(
      "--focus-range", options->focusRange,
      "keep everything between two depths in focus, NEAR:FAR in slopes (the near end the larger) or NEARmm:FARmm "
      "from the main lens (needs optics); the blur beyond grows as a lens focused at the range's end blurs it");
  command
      ->add_option("--depth", options->depthMap,
                   "with --focus-range: disparity map of the centre view (as `lfcam depth` writes; default: "
                   "estimated on the way with lfcam depth's defaults)")
      ->needs(focusRange);
  focusRange->excludes(slope)->excludes(alpha)->excludes(focusAt)->excludes(focusPlane)->excludes(tilt);
  slope->excludes(alpha);
  focusAt->excludes(slope)->excludes(alpha);
  focusPlane->excludes(slope)->excludes(alpha)->excludes(focusAt)->excludes(tilt);
  tilt->excludes(focusAt);
  addCameraOptions(*command, options->camera);
  command->add_option("-o,--output", options->output, "output image (.png, .tif, .exr, .jpg, .pfm)")->required();
  addBitDepthOption(*command, options->depth);
  command->callback([options, &job] {
    job = [options]() -> Status {
      const bool tilted = options->tilt || !options->focusPlane.empty();
      const bool spread = !options->focusRange.empty();
      if (!options->slope && !options->alpha && options->focusAt.empty() && options->focusPlane.empty() && !spread)
        return makeError(ErrorCode::Usage,
                         "refocus: give the focus depth with --slope, --alpha, --focus-at, --focus-plane or "
                         "--focus-range");
      if (spread && (!options->camera.isFullApertureFast() || options->upsample > 1))
        return makeError(ErrorCode::Usage,
                         "refocus: a focus range is rendered with the full aperture and the fast method only (no "
                         "--aperture*, --method, --supersampling, --beta or --upsample)");
      if (tilted && !options->camera.isFullApertureFast())
        return makeError(ErrorCode::Usage,
                         "refocus: a tilted plane of focus is rendered with the full aperture and the fast method "
                         "only (no --aperture*, --method, --supersampling or --beta)");
      if (options->upsample < 1 || options->upsample > kMaxUpsampleFactor)
        return makeError(ErrorCode::Usage, "--upsample: expected 1 to " + std::to_string(kMaxUpsampleFactor) +
                                               ", got " + std::to_string(options->upsample));
      if (options->upsample > 1 && (tilted || !options->camera.isFullApertureFast()))
        return makeError(ErrorCode::Usage,
                         "refocus: --upsample renders a fronto-parallel focus with the full aperture and the fast "
                         "method only (no --tilt, --focus-plane, --aperture*, --method, --supersampling or --beta)");
      std::array<ImagePoint, 3> planePoints{};
      if (!options->focusPlane.empty()) {
        auto parsed = parseFocusPlanePoints(options->focusPlane);
        if (!parsed) return makeError(parsed.error().code, "--focus-plane: " + parsed.error().message);
        planePoints = *parsed;
      }
      LFCAM_ASSIGN_OR_RETURN(auto writeOptions, imageWriteOptionsFor(options->output, options->depth));
      std::optional<std::pair<double, double>> point;
      if (!options->focusAt.empty()) {
        LFCAM_ASSIGN_OR_RETURN(auto parsed, parsePair(options->focusAt, "--focus-at"));
        point = parsed;
      }
      std::optional<Image> disparity;
      if (!options->depthMap.empty()) {
        LFCAM_ASSIGN_OR_RETURN(auto read, readImage(options->depthMap));
        disparity = std::move(read);
      }
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      if (spread) {
        LFCAM_ASSIGN_OR_RETURN(auto range, parseFocusRange(options->focusRange, lightField, options->input.path));
        if (!disparity) {
          auto estimated = estimateDepth(lightField);
          if (!estimated)
            return makeError(estimated.error().code, options->input.path + ": " + estimated.error().message);
          disparity = std::move(estimated->disparity);
        }
        auto photo = refocusSpread(lightField, *disparity, range.first, range.second);
        if (!photo)
          return makeError(photo.error().code, (options->depthMap.empty() ? options->input.path : options->depthMap) +
                                                   ": " + photo.error().message);
        return writeImage(options->output, *photo, writeOptions);
      }
      LFCAM_ASSIGN_OR_RETURN(auto camera, cameraFrom(options->camera, lightField, options->input.path));
      double slopeValue = options->slope.value_or(0.0);
      if (options->alpha) {
        LFCAM_ASSIGN_OR_RETURN(slopeValue, slopeFromAlpha(lightField, *options->alpha, options->input.path));
      }
      if (point) {
        auto found = slopeAtPixel(lightField, point->first, point->second);
        if (!found) return makeError(found.error().code, "--focus-at: " + found.error().message);
        slopeValue = *found;
        std::printf("slope %.4f\n", slopeValue);
      }
      if (!options->focusPlane.empty()) {
        auto plane = focusPlaneThroughPoints(lightField, planePoints);
        if (!plane) return makeError(plane.error().code, "--focus-plane: " + plane.error().message);
        std::printf("focus plane: slope %.4f at the centre, gradient %.5f, %.5f per pixel\n", plane->slope,
                    plane->gradientX, plane->gradientY);
        return writeImage(options->output, refocusTilted(lightField, *plane), writeOptions);
      }
      if (options->tilt) {
        const FocusPlane plane = focusPlaneFromTilt(lightField, slopeValue, *options->tilt, options->tiltDirection);
        return writeImage(options->output, refocusTilted(lightField, plane), writeOptions);
      }
      if (options->upsample > 1) {
        LFCAM_ASSIGN_OR_RETURN(auto photo, refocusUpsampled(lightField, slopeValue, options->upsample));
        return writeImage(options->output, photo, writeOptions);
      }
      return renderPhotos(lightField, camera, {slopeValue},
                          [&](int, double, Image&& photo) { return writeImage(options->output, photo, writeOptions); });
    };
  });
}

}  // namespace lfcam::cli
