// lfcam refocus INPUT (--slope D | --alpha A | --focus-at X,Y) -o OUT: a photograph focused after
// the fact (Equation 6), through any synthetic aperture and lens plane (Equation 5).
#include <cstdio>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "image_output.hpp"
#include "lfcam/focal_stack.hpp"
#include "lfcam/synthetic_camera.hpp"
#include "render_cli.hpp"

namespace lfcam::cli {

void addRefocusCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::optional<double> slope, alpha;
    std::string focusAt;
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
  slope->excludes(alpha);
  focusAt->excludes(slope)->excludes(alpha);
  addCameraOptions(*command, options->camera);
  command->add_option("-o,--output", options->output, "output image (.png, .tif, .exr, .jpg, .pfm)")->required();
  addBitDepthOption(*command, options->depth);
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (!options->slope && !options->alpha && options->focusAt.empty())
        return makeError(ErrorCode::Usage, "refocus: give the focus depth with --slope, --alpha or --focus-at");
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
      return renderPhotos(lightField, camera, {slopeValue},
                          [&](int, double, Image&& photo) { return writeImage(options->output, photo, writeOptions); });
    };
  });
}

}  // namespace lfcam::cli
