// lfcam stack INPUT (--slopes A:B:N | --alphas A:B:N) -o DIR: a focal stack, one photograph per
// focus depth (slice_000.png, ...), and stack.json naming the slope (and alpha) of each.
#include <memory>

#include "commands.hpp"
#include "image_output.hpp"
#include "lfcam/photo/photo_request.hpp"
#include "lfcam/render/focal_stack.hpp"
#include "photo/focal_stack_output.hpp"
#include "photo_options.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addStackCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::string slopes, alphas;
    PhotoOptions photo;
    std::string extension = "png", depth;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("stack", "a focal stack: one refocused photograph per depth");
  addInputOptions(*command, options->input);
  auto* slopes = command->add_option("--slopes", options->slopes, "FIRST:LAST:COUNT slopes, pixels per view step");
  auto* alphas = command->add_option("--alphas", options->alphas, "FIRST:LAST:COUNT film depths (needs optics)");
  slopes->excludes(alphas);
  addPhotoOptions(*command, options->photo, {"aperture", "lens", "sampling"}, {"upsample"});
  command->add_option("--format", options->extension, "image format of the slices")
      ->check(CLI::IsMember({"png", "tif", "exr", "jpg", "pfm"}));
  addBitDepthOption(*command, options->depth);
  command->add_option("-o,--output", options->output, "output folder")->required();
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (options->slopes.empty() == options->alphas.empty())
        return makeError(ErrorCode::Usage, "stack: give the depths with --slopes or --alphas");
      LFCAM_ASSIGN_OR_RETURN(auto values, parseEvenlySpaced(options->slopes.empty() ? options->alphas : options->slopes,
                                                            options->slopes.empty() ? "--alphas" : "--slopes"));
      LFCAM_ASSIGN_OR_RETURN(auto writeOptions, imageWriteOptionsFor(std::filesystem::path(options->output) /
                                                                         stackSliceName(0, options->extension),
                                                                     options->depth));
      PhotoRequest slice;
      slice.slope = 0;  // each slice sets its own
      LFCAM_ASSIGN_OR_RETURN(auto request, photoRequestFrom(options->photo, slice));
      LFCAM_TRY(checkPhotoRequest(request));
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      LFCAM_ASSIGN_OR_RETURN(auto camera, resolvePhoto(request, lightField, {.inputName = options->input.path}));
      std::vector<double> slopeValues = values;
      if (!options->alphas.empty())
        for (double& value : slopeValues) {
          LFCAM_ASSIGN_OR_RETURN(value, slopeFromAlpha(lightField, value, options->input.path));
        }
      ProgressBar bar("focal stack");
      return writeFocalStack(options->output, lightField, camera, slopeValues, options->extension, writeOptions,
                             [&](double fraction) { bar(fraction); });
    };
  });
}

}  // namespace lfcam::cli
