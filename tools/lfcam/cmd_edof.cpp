// lfcam edof INPUT -o OUT [--depth DEPTH.pfm]: a photograph with everything in focus, composed
// from photographs refocused at many depths (section 5.2, Figure 15; all_in_focus.hpp). With
// --depth, the slices follow that disparity map (e.g. from `lfcam depth`); without, a focus
// measure on the focal stack chooses them.
#include <memory>
#include <optional>

#include "commands.hpp"
#include "focused_input.hpp"
#include "image_output.hpp"
#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/focused/focused_render.hpp"
#include "lfcam/io/color_map.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam::cli {

namespace {

// A focused plenoptic capture's total focus: each pixel rendered at its own virtual depth, from the
// map given or estimated (focused_depth.hpp, focused_render.hpp).
Result<Image> focusedTotalFocus(const InputOptions& input, const FocusedOptions& focused,
                                const std::string& depthPath) {
  LFCAM_ASSIGN_OR_RETURN(auto capture, loadFocusedInput(input, focused));
  std::optional<Image> virtualDepth;
  if (!depthPath.empty()) {
    LFCAM_ASSIGN_OR_RETURN(virtualDepth, readImage(depthPath));
  }
  auto photo = renderTotalFocus(capture.image, capture.calibration, pixelsPerLens(focused, capture.calibration),
                                virtualDepth ? &*virtualDepth : nullptr);
  if (!photo) return makeError(photo.error().code, input.path + ": " + photo.error().message);
  return std::move(photo).value();
}

}  // namespace

void addEdofCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    FocusedOptions focused;
    std::string output, depth, labels, bitDepth;
    AllInFocusOptions edof;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command =
      app.add_subcommand("edof", "extended depth of field: all-in-focus photomontage of a focal stack (Figure 15)");
  addInputOptions(*command, options->input);
  addFocusedOptions(*command, options->focused);
  command->add_option("-o,--output", options->output, "output image (.png, .tif, .exr, .jpg, .pfm)")->required();
  addBitDepthOption(*command, options->bitDepth);
  command->add_option("--depth", options->depth, "disparity map of the centre view (as `lfcam depth` writes)");
  command->add_option("--slices-png", options->labels, "the slope chosen per pixel, colour-mapped, for people");
  command->add_option("--min", options->edof.disparityMin, "smallest slope of the focal stack");
  command->add_option("--max", options->edof.disparityMax, "largest slope of the focal stack");
  command->add_option("--step", options->edof.sliceStep, "slope between slices (default: 1 / (views - 1))")
      ->check(CLI::PositiveNumber);
  command->callback([options, command, &job] {
    job = [options, command]() -> Status {
      LFCAM_ASSIGN_OR_RETURN(auto writeOptions, imageWriteOptionsFor(options->output, options->bitDepth));
      if (isFocusedInput(options->input, options->focused)) {
        if (!options->labels.empty() || command->count("--min") || command->count("--max") || command->count("--step"))
          return makeError(ErrorCode::Usage, options->input.path +
                                                 ": --slices-png, --min, --max and --step are for "
                                                 "light fields, not for a focused plenoptic capture");
        LFCAM_ASSIGN_OR_RETURN(auto photo, focusedTotalFocus(options->input, options->focused, options->depth));
        return writeImage(options->output, photo, writeOptions);
      }
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      std::optional<Image> disparity;
      if (!options->depth.empty()) {
        LFCAM_ASSIGN_OR_RETURN(auto read, readImage(options->depth));
        disparity = std::move(read);
        options->edof.disparity = &*disparity;
      }
      auto result = allInFocus(lightField, options->edof);
      if (!result) return makeError(result.error().code, options->input.path + ": " + result.error().message);
      LFCAM_TRY(writeImage(options->output, result->photo, writeOptions));
      if (!options->labels.empty())
        LFCAM_TRY(writeImage(options->labels, colorMap(result->slope, result->slopes.front(), result->slopes.back())));
      return {};
    };
  });
}

}  // namespace lfcam::cli
