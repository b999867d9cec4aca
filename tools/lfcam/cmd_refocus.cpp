// lfcam refocus INPUT (--slope D | --alpha A) -o OUT: a photograph focused after the fact by
// shift-and-add of the sub-aperture images (Equation 6).
#include <memory>
#include <optional>

#include "commands.hpp"
#include "lfcam/image_io.hpp"
#include "lfcam/refocus.hpp"

namespace lfcam::cli {

void addRefocusCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::optional<double> slope, alpha;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("refocus", "refocus a light field (shift-and-add, Equation 6)");
  addInputOptions(*command, options->input);
  auto* slope = command->add_option("--slope", options->slope,
                                    "disparity brought into focus, pixels per view step (HCI convention)");
  auto* alpha = command->add_option("--alpha", options->alpha,
                                    "relative depth of the synthetic film plane (needs optics metadata)")
                    ->check(CLI::PositiveNumber);
  slope->excludes(alpha);
  command->add_option("-o,--output", options->output, "output image (.png, .tif, .exr, .jpg, .pfm)")->required();
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (!options->slope && !options->alpha)
        return makeError(ErrorCode::Usage, "refocus: give the focus depth with --slope or --alpha");
      auto lightField = loadInput(options->input);
      if (!lightField) return lightField.error();
      double slopeValue = options->slope.value_or(0.0);
      if (options->alpha) {
        const auto& optics = lightField->metadata.optics;
        if (!optics)
          return makeError(ErrorCode::Usage, options->input.path +
                                                 ": no optics metadata, so --alpha cannot be converted to a "
                                                 "slope; use --slope (pixels per view step)");
        slopeValue = optics->slopeFromAlpha(*options->alpha);
      }
      return writeImage(options->output, refocus(*lightField, slopeValue));
    };
  });
}

}  // namespace lfcam::cli
