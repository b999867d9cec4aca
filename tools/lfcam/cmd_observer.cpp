// lfcam observer INPUT --u U --v V [--beta B] [--clamp] -o OUT: the photograph of a pinhole moved
// within the lens plane (parallax) and along the axis (beta, perspective): Equation 7, the
// photograph request (photo_request.hpp) of a pinhole aperture at (U, V) on the real film plane.
#include <array>
#include <memory>

#include "commands.hpp"
#include "image_output.hpp"
#include "lfcam/photo/photo_request.hpp"

namespace lfcam::cli {

void addObserverCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    double u = 0, v = 0, beta = 1;
    bool clamp = false;
    std::string output, depth;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("observer", "move the observer: a pinhole view from anywhere (Equation 7)");
  addInputOptions(*command, options->input);
  command->add_option("--u", options->u, "pinhole position across, view steps from the centre view")->required();
  command->add_option("--v", options->v, "pinhole position down, view steps from the centre view")->required();
  command->add_option("--beta", options->beta, "relative position of the pinhole's plane (needs optics)")
      ->check(CLI::PositiveNumber);
  command->add_flag("--clamp", options->clamp,
                    "rays outside the lens take the closest available ray (Figure 7) instead of going black");
  command->add_option("-o,--output", options->output, "output image (.png, .tif, .exr, .jpg, .pfm)")->required();
  addBitDepthOption(*command, options->depth);
  command->callback([options, &job] {
    job = [options]() -> Status {
      const PhotoRequest request{.slope = 0.0,
                                 .aperture = 0.0,
                                 .apertureCentre = std::array<double, 2>{options->u, options->v},
                                 .clamp = options->clamp,
                                 .beta = options->beta};
      LFCAM_TRY(checkPhotoRequest(request));
      LFCAM_ASSIGN_OR_RETURN(auto writeOptions, imageWriteOptionsFor(options->output, options->depth));
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      LFCAM_ASSIGN_OR_RETURN(auto photo, renderPhoto(lightField, request, {.inputName = options->input.path}));
      return writeImage(options->output, photo, writeOptions);
    };
  });
}

}  // namespace lfcam::cli
