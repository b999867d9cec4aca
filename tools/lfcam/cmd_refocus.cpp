// lfcam refocus INPUT (--slope D | --alpha A | --focus-at X,Y) -o OUT: a photograph focused after
// the fact (Equation 6), through any synthetic aperture and lens plane (Equation 5); or focused on
// a tilted plane (tilted_focus.hpp): --focus-plane X1,Y1:X2,Y2:X3,Y3, or --tilt T [--tilt-direction
// DEG] about the --slope or --alpha at the image centre; --upsample K renders it on a grid K times
// finer (upsampled_refocus.hpp).
#include <cstdio>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "image_output.hpp"
#include "lfcam/focal_stack.hpp"
#include "lfcam/synthetic_camera.hpp"
#include "lfcam/tilted_focus.hpp"
#include "lfcam/upsampled_refocus.hpp"
#include "render_cli.hpp"

namespace lfcam::cli {

void addRefocusCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::optional<double> slope, alpha;
    std::string focusAt, focusPlane;
    std::optional<double> tilt;
    double tiltDirection = 0;
    int upsample = 1;
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
      if (!options->slope && !options->alpha && options->focusAt.empty() && options->focusPlane.empty())
        return makeError(ErrorCode::Usage,
                         "refocus: give the focus depth with --slope, --alpha, --focus-at or --focus-plane");
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
        LFCAM_ASSIGN_OR_RETURN(planePoints, parseFocusPlanePoints(options->focusPlane));
      }
      LFCAM_ASSIGN_OR_RETURN(auto writeOptions, imageWriteOptionsFor(options->output, options->depth));
      std::optional<std::pair<double, double>> point;
      if (!options->focusAt.empty()) {
        LFCAM_ASSIGN_OR_RETURN(auto parsed, parsePair(options->focusAt, "--focus-at"));
        point = parsed;
      }
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
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
