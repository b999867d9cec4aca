// lfcam depth INPUT -o DEPTH.pfm [--metric] [--confidence FILE] [--png FILE] [--distance FILE] [--ply FILE
// [--min-confidence C]] [--options FILE.json] [--SETTING VALUE ...]: the disparity seen through the aperture
// centre (pixels per view step, HCI convention), from the correspondence and defocus cues of the light field
// (depth.hpp); every setting of depth_knobs.hpp as a flag, which wins over the options file. With the optics
// known, distances in mm (--metric, --distance) and a coloured point cloud (--ply, point_cloud.hpp).
#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <variant>

#include "commands.hpp"
#include "focused_input.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/edof/depth_knobs.hpp"
#include "lfcam/edof/point_cloud.hpp"
#include "lfcam/focused/focused_depth.hpp"
#include "lfcam/io/color_map.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam::cli {

namespace {

// A focused plenoptic capture: its virtual depth on the photograph's frame (focused_depth.hpp).
template <class Options>
Status focusedDepth(const Options& options, const CLI::App& command) {
  if (!options.ply.empty() || !options.optionsFile.empty())
    return makeError(
        ErrorCode::Usage,
        options.input.path + ": --ply and --options are for light fields, not a focused plenoptic capture");
  for (const DepthKnob& knob : depthKnobs())
    if (command.count(std::string("--") + knob.name) > 0)
      return makeError(ErrorCode::Usage, options.input.path + ": --" + knob.name +
                                             " is for light fields, not for a "
                                             "focused plenoptic capture");
  LFCAM_ASSIGN_OR_RETURN(auto capture, loadFocusedInput(options.input, options.focused));
  FocusedDepthRequest request;
  request.pixelsPerLens = pixelsPerLens(options.focused, capture.calibration);
  std::optional<Image> distance;
  if (options.metric || !options.distance.empty())
    LFCAM_TRY(checkFocusedOptics(capture.calibration, options.input.path));
  auto depth = estimateFocusedDepth(capture.image, capture.calibration, request);
  if (!depth) return makeError(depth.error().code, options.input.path + ": " + depth.error().message);
  if (options.metric || !options.distance.empty()) {
    LFCAM_ASSIGN_OR_RETURN(distance, focusedDistanceMap(capture.calibration, depth->virtualDepth, options.input.path));
  }
  LFCAM_TRY(writeImage(options.output, options.metric ? *distance : depth->virtualDepth));
  if (!options.distance.empty()) LFCAM_TRY(writeImage(options.distance, *distance));
  if (!options.confidence.empty()) LFCAM_TRY(writeImage(options.confidence, depth->confidence));
  if (!options.png.empty()) {
    float lo = 1e30f, hi = 0;
    for (const float v : depth->virtualDepth.pixels()) lo = std::min(lo, v), hi = std::max(hi, v);
    LFCAM_TRY(writeImage(options.png, colorMap(depth->virtualDepth, lo, hi)));
  }
  return {};
}

}  // namespace

void addDepthCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    FocusedOptions focused;
    std::string output, confidence, png, distance, ply, optionsFile;
    bool metric = false;
    double minConfidence = 0;
    DepthOptions flags;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "depth", "disparity map of the centre view (pixels per view step), and distance when the optics are known");
  addInputOptions(*command, options->input);
  addFocusedOptions(*command, options->focused);
  command->add_option("-o,--output", options->output, "disparity map (.pfm as the HCI benchmark, .exr, .tif)")
      ->required();
  command->add_option("--confidence", options->confidence, "confidence map in [0, 1] (.pfm, .exr, .tif, .png)");
  command->add_option("--png", options->png, "the disparity colour-mapped (Turbo: far blue, near red) for people");
  command->add_option("--distance", options->distance,
                      "distance from the main lens in mm, float image (needs optics with a focal length)");
  command->add_flag("--metric", options->metric,
                    "the output holds the distance from the main lens in mm instead of the disparity (needs optics "
                    "with a focal length: decoded raws, simulator captures, HCI folders with parameters.cfg, focused "
                    "captures whose calibration holds lfcam_optics)");
  command->add_option("--ply", options->ply,
                      "coloured point cloud (binary PLY, mm: x right, y down, z away; a confidence property per "
                      "point) for MeshLab, Open3D (needs optics with a focal length)");
  command->add_option("--min-confidence", options->minConfidence, "points of --ply less sure than this are left out")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
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
      // Outputs into a missing folder are refused before the work, not after it.
      for (const std::string* file :
           {&options->output, &options->confidence, &options->png, &options->distance, &options->ply}) {
        const std::filesystem::path folder = std::filesystem::path(*file).parent_path();
        std::error_code ec;
        if (!file->empty() && !folder.empty() && !std::filesystem::is_directory(folder, ec))
          return makeError(ErrorCode::Usage, *file + ": the folder " + folder.string() + " does not exist");
      }
      if (isFocusedInput(options->input, options->focused)) return focusedDepth(*options, *command);
      DepthOptions depthOptions;
      if (!options->optionsFile.empty()) LFCAM_TRY(readDepthOptions(options->optionsFile, depthOptions));
      for (const DepthKnob& knob : depthKnobs())  // a flag given wins over the file
        if (command->count(std::string("--") + knob.name) > 0)
          std::visit([&](auto member) { depthOptions.*member = options->flags.*member; }, knob.member);
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      const bool needsOptics = options->metric || !options->distance.empty() || !options->ply.empty();
      if (needsOptics && !(lightField.metadata.optics && lightField.metadata.optics->focalLengthMm))
        return makeError(ErrorCode::Usage,
                         options->input.path +
                             ": no optics metadata with a focal length, so no distance (--metric, --distance, --ply); "
                             "the disparity map needs none");
      auto depth = estimateDepth(lightField, depthOptions);
      if (!depth) return makeError(depth.error().code, options->input.path + ": " + depth.error().message);
      std::optional<Image> distance;
      if (options->metric || !options->distance.empty()) {
        LFCAM_ASSIGN_OR_RETURN(distance, distanceMap(lightField.metadata, depth->disparity));
      }
      std::optional<PointCloud> cloud;
      if (!options->ply.empty()) {
        LFCAM_ASSIGN_OR_RETURN(
            cloud, pointCloudFromDepth(lightField, depth->disparity, depth->confidence, options->minConfidence));
      }
      LFCAM_TRY(writeImage(options->output, options->metric ? *distance : depth->disparity));
      if (!options->confidence.empty()) LFCAM_TRY(writeImage(options->confidence, depth->confidence));
      if (!options->png.empty())
        LFCAM_TRY(writeImage(options->png, colorMap(depth->disparity, depth->disparityMin, depth->disparityMax)));
      if (!options->distance.empty()) LFCAM_TRY(writeImage(options->distance, *distance));
      if (cloud) LFCAM_TRY(writePly(options->ply, *cloud));
      return {};
    };
  });
}

}  // namespace lfcam::cli
