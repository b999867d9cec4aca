// lfcam depth INPUT -o DEPTH.pfm [--confidence FILE] [--png FILE] [--distance FILE] [--options
// FILE.json] [--SETTING VALUE ...]: the disparity seen through the aperture centre (pixels per view
// step, HCI convention), from the correspondence and defocus cues of the light field (depth.hpp);
// every setting of depth_knobs.hpp as a flag, which wins over the options file.
#include <memory>
#include <optional>
#include <string>
#include <variant>

#include "commands.hpp"
#include "lfcam/color_map.hpp"
#include "lfcam/depth.hpp"
#include "lfcam/depth_knobs.hpp"
#include "lfcam/image_io.hpp"

namespace lfcam::cli {

void addDepthCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::string output, confidence, png, distance, optionsFile;
    DepthOptions flags;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "depth", "disparity map of the aperture centre (pixels per view step), and distance when the optics are known");
  addInputOptions(*command, options->input);
  command->add_option("-o,--output", options->output, "disparity map (.pfm as the HCI benchmark, .exr, .tif)")
      ->required();
  command->add_option("--confidence", options->confidence, "confidence map in [0, 1] (.pfm, .exr, .tif, .png)");
  command->add_option("--png", options->png, "the disparity colour-mapped (Turbo: far blue, near red) for people");
  command->add_option("--distance", options->distance,
                      "distance from the main lens in mm, float image (needs optics with a focal length)");
  command->add_option("--options", options->optionsFile,
                      "settings from a JSON object of NAME: number, NAME any setting below; the flags win");
  for (const DepthKnob& knob : depthKnobs()) {
    const std::string flag = std::string("--") + knob.name, help = std::string(knob.stage) + ": " + knob.help;
    std::visit(
        [&](auto member) {
          command->add_option(flag, options->flags.*member, help)
              ->capture_default_str()
              ->check(CLI::Range(knob.min, knob.max));
        },
        knob.member);
  }
  command->callback([options, command, &job] {
    job = [options, command]() -> Status {
      DepthOptions depthOptions;
      if (!options->optionsFile.empty()) LFCAM_TRY(readDepthOptions(options->optionsFile, depthOptions));
      for (const DepthKnob& knob : depthKnobs())  // a flag given wins over the file
        if (command->count(std::string("--") + knob.name) > 0)
          std::visit([&](auto member) { depthOptions.*member = options->flags.*member; }, knob.member);
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      if (!options->distance.empty() && !(lightField.metadata.optics && lightField.metadata.optics->focalLengthMm))
        return makeError(ErrorCode::Usage, options->input.path +
                                               ": no optics metadata with a focal length, so --distance cannot be "
                                               "computed; the disparity map needs none");
      auto depth = estimateDepth(lightField, depthOptions);
      if (!depth) return makeError(depth.error().code, options->input.path + ": " + depth.error().message);
      LFCAM_TRY(writeImage(options->output, depth->disparity));
      if (!options->confidence.empty()) LFCAM_TRY(writeImage(options->confidence, depth->confidence));
      if (!options->png.empty())
        LFCAM_TRY(writeImage(options->png, colorMap(depth->disparity, depth->disparityMin, depth->disparityMax)));
      if (!options->distance.empty()) {
        LFCAM_ASSIGN_OR_RETURN(auto distance, distanceMap(lightField.metadata, depth->disparity));
        LFCAM_TRY(writeImage(options->distance, distance));
      }
      return {};
    };
  });
}

}  // namespace lfcam::cli
