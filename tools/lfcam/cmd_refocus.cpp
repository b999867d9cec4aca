// lfcam refocus INPUT -o OUT: one photograph of Equation 5, every field of the photograph request
// (photo_request.hpp) a flag: the focus (--slope, --alpha, --focus-at, --focus-plane, --tilt,
// --focus-range with --depth), the aperture (--aperture or --f-number, --aperture-shape,
// --aperture-centre, --aperture-mask, --clamp), the lens plane (--beta) and the sampling
// (--method, --supersampling, --upsample), in any combination.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "focused_input.hpp"
#include "image_output.hpp"
#include "lfcam/focused/focused_render.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/photo/photo_request.hpp"
#include "photo_options.hpp"

namespace lfcam::cli {

namespace {

// A focused plenoptic capture refocused at one virtual depth, through a disc of each micro-image
// (focused_render.hpp): of the photograph request, only the aperture's size and centre apply.
template <class Options>
Status focusedRefocus(const Options& options) {
  for (const auto& [name, option] : options.photo.options)
    if (option->count() && name != "aperture" && name != "aperture-centre")
      return makeError(ErrorCode::Usage, options.input.path + ": --" + name +
                                             " is for light fields; a focused plenoptic capture takes "
                                             "--virtual-depth, --aperture, --aperture-centre and --patches");
  if (!(options.virtualDepth > 0))
    return makeError(ErrorCode::Usage, options.input.path + ": a focused plenoptic capture needs --virtual-depth");
  LFCAM_ASSIGN_OR_RETURN(auto photoRequest, photoRequestFrom(options.photo));
  LFCAM_ASSIGN_OR_RETURN(auto writeOptions, imageWriteOptionsFor(options.output, options.depth));
  LFCAM_ASSIGN_OR_RETURN(auto capture, loadFocusedInput(options.input, options.focused));
  FocusedRenderRequest request;
  request.pixelsPerLens = pixelsPerLens(options.focused, capture.calibration);
  request.virtualDepth = options.virtualDepth;
  request.nearestLensOnly = options.patches;
  if (photoRequest.aperture) request.aperture = *photoRequest.aperture;
  if (photoRequest.apertureCentre) request.viewpoint = *photoRequest.apertureCentre;
  auto photo = renderFocused(capture.image, capture.calibration, request);
  if (!photo) return makeError(photo.error().code, options.input.path + ": " + photo.error().message);
  return writeImage(options.output, *photo, writeOptions);
}

}  // namespace

void addRefocusCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    FocusedOptions focused;
    PhotoOptions photo;
    std::string output, depth;
    double virtualDepth = 0;
    bool patches = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("refocus",
                                         "a photograph after the fact: any focus, aperture, viewpoint "
                                         "(Equations 5-7)");
  addInputOptions(*command, options->input);
  addPhotoOptions(*command, options->photo, {"focus", "aperture", "lens", "sampling"});
  addFocusedOptions(*command, options->focused);
  command
      ->add_option("--virtual-depth", options->virtualDepth,
                   "focused captures: the virtual depth to focus at (with --aperture and --aperture-centre as shares "
                   "of a micro-image's usable radius)")
      ->check(CLI::PositiveNumber);
  command->add_flag("--patches", options->patches,
                    "focused captures: Lumsdaine and Georgiev's basic rendering, one patch per micro-image");
  command->add_option("-o,--output", options->output, "output image (.png, .tif, .exr, .jpg, .pfm)")->required();
  addBitDepthOption(*command, options->depth);
  command->callback([options, &job] {
    job = [options]() -> Status {
      // Every check that needs no light field before reading it, so that a bad request fails fast.
      if (isFocusedInput(options->input, options->focused)) return focusedRefocus(*options);
      if (options->virtualDepth > 0 || options->patches)
        return makeError(ErrorCode::Usage, options->input.path +
                                               ": --virtual-depth and --patches are for a focused "
                                               "plenoptic capture (its calibration beside it, or "
                                               "--focused-calibration)");
      LFCAM_ASSIGN_OR_RETURN(auto request, photoRequestFrom(options->photo));
      LFCAM_TRY(checkPhotoRequest(request));
      LFCAM_ASSIGN_OR_RETURN(auto writeOptions, imageWriteOptionsFor(options->output, options->depth));
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      LFCAM_ASSIGN_OR_RETURN(auto photo, resolvePhoto(request, lightField, {.inputName = options->input.path}));
      const FocusPlane& plane = photo.film.plane;
      if (request.focusAt) std::printf("slope %.4f\n", plane.slope);
      if (request.focusPlane)
        std::printf("focus plane: slope %.4f at the centre, gradient %.5f, %.5f per pixel\n", plane.slope,
                    plane.gradientX, plane.gradientY);
      LFCAM_ASSIGN_OR_RETURN(auto image, renderPhoto(lightField, photo));
      return writeImage(options->output, image, writeOptions);
    };
  });
}

}  // namespace lfcam::cli
