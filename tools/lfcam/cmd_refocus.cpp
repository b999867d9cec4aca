// lfcam refocus INPUT -o OUT: one photograph of Equation 5, every field of the photograph request
// (photo_request.hpp) a flag: the focus (--slope, --alpha, --focus-at, --focus-plane, --tilt,
// --focus-range with --depth), the aperture (--aperture or --f-number, --aperture-shape,
// --aperture-centre, --aperture-mask, --clamp), the lens plane (--beta) and the sampling
// (--method, --supersampling, --upsample), in any combination.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "image_output.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/photo/photo_request.hpp"
#include "photo_options.hpp"

namespace lfcam::cli {

void addRefocusCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    PhotoOptions photo;
    std::string output, depth;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("refocus",
                                         "a photograph after the fact: any focus, aperture, viewpoint "
                                         "(Equations 5-7)");
  addInputOptions(*command, options->input);
  addPhotoOptions(*command, options->photo, {"focus", "aperture", "lens", "sampling"});
  command->add_option("-o,--output", options->output, "output image (.png, .tif, .exr, .jpg, .pfm)")->required();
  addBitDepthOption(*command, options->depth);
  command->callback([options, &job] {
    job = [options]() -> Status {
      // Every check that needs no light field before reading it, so that a bad request fails fast.
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
