// lfcam info INPUT [--json] [--whites whites.json]: what a light-field input is, without reading its
// samples when the format allows, and for a raw which white decoding it takes.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "focused_input.hpp"
#include "lytro_info.hpp"
#include "raw_io/lytro_container.hpp"

namespace lfcam::cli {

namespace {

nlohmann::json infoJson(const std::string& path, const LightFieldInfo& info) {
  const LightFieldShape& shape = info.shape;
  nlohmann::json json = {{"path", path},
                         {"format", formatName(info.format)},
                         {"angular", {shape.nu, shape.nv}},
                         {"spatial", {shape.ns, shape.nt}},
                         {"channels", shape.channels},
                         {"weight", info.hasWeight}};
  const LightFieldMetadata& meta = info.metadata;
  if (meta.disparityMin && meta.disparityMax) json["disparity_range"] = {*meta.disparityMin, *meta.disparityMax};
  if (meta.optics) {
    json["optics"] = {{"lens_step_mm", meta.optics->lensStepMm},
                      {"spatial_step_mm", meta.optics->spatialStepMm},
                      {"lens_to_microlens_mm", meta.optics->lensToMicrolensMm}};
    if (meta.optics->focalLengthMm) json["optics"]["focal_length_mm"] = *meta.optics->focalLengthMm;
  }
  if (!meta.source.empty()) json["source"] = meta.source;
  return json;
}

void printText(const std::string& path, const LightFieldInfo& info) {
  const LightFieldShape& shape = info.shape;
  std::printf("%s: %s light field\n", path.c_str(), formatName(info.format));
  std::printf("  angular (u, v): %d x %d views\n", shape.nu, shape.nv);
  std::printf("  spatial (s, t): %d x %d pixels\n", shape.ns, shape.nt);
  std::printf("  channels: %d\n", shape.channels);
  std::printf("  weight: %s\n", info.hasWeight ? "yes" : "no");
  const LightFieldMetadata& meta = info.metadata;
  if (meta.disparityMin && meta.disparityMax)
    std::printf("  disparity range: %g to %g pixels per view step\n", *meta.disparityMin, *meta.disparityMax);
  if (meta.optics)
    std::printf(
        "  optics: view step %g mm on the lens, sample step %g mm on the microlens plane, lens to "
        "microlenses %g mm\n",
        meta.optics->lensStepMm, meta.optics->spatialStepMm, meta.optics->lensToMicrolensMm);
  if (!meta.source.empty()) std::printf("  source: %s\n", meta.source.c_str());
}

// white: the white image given, if any.
nlohmann::json focusedInfoJson(const std::string& path, const std::string& white, const FocusedCapture& capture) {
  const FocusedCalibration& c = capture.calibration;
  nlohmann::json types = nlohmann::json::array();
  for (const LensType& type : c.lensTypes)
    types.push_back({{"offset", {type.offset[0], type.offset[1]}},
                     {"virtual_depth_range", {type.minVirtualDepth, type.maxVirtualDepth}}});
  nlohmann::json json = {
      {"path", path},
      {"format", "focused plenoptic capture"},
      {"image", {capture.image.width(), capture.image.height()}},
      {"channels", capture.image.channels()},
      {"packing", packingName(c.grid.packing)},
      {"micro_image_diameter_px", c.diameterPx()},
      {"micro_images", {c.grid.columns, c.grid.rows}},
      {"micro_image_orientation", c.orientation == MicroImageOrientation::Upright ? "upright" : "inverted"},
      {"border_px", c.borderPx},
      {"lens_types", types},
      {"calibration", !capture.selfCalibration ? capture.calibrationPath.string()
                      : white.empty()          ? "self-calibrated from the capture"
                                               : "self-calibrated from the white image " + white}};
  if (c.totalCoveringPlane) json["total_covering_plane"] = *c.totalCoveringPlane;
  return json;
}

void printFocusedText(const nlohmann::json& json) {
  const auto& types = json["lens_types"];
  std::printf("%s: focused plenoptic capture (plenoptic 2.0), %zu lens type%s, %s micro-images\n",
              json["path"].get<std::string>().c_str(), types.size(), types.size() == 1 ? "" : "s",
              json["packing"].get<std::string>().c_str());
  std::printf("  image: %d x %d pixels, %d channels\n", json["image"][0].get<int>(), json["image"][1].get<int>(),
              json["channels"].get<int>());
  std::printf("  micro-images: %.3f pixels across, %d x %d, %s (%s), border %g pixels\n",
              json["micro_image_diameter_px"].get<double>(), json["micro_images"][0].get<int>(),
              json["micro_images"][1].get<int>(), json["micro_image_orientation"].get<std::string>().c_str(),
              json["micro_image_orientation"] == "upright" ? "Galilean" : "Keplerian", json["border_px"].get<double>());
  for (std::size_t t = 0; t < types.size(); ++t)
    std::printf("  lens type %zu: offset (%g, %g), sharp at virtual depths %g to %g\n", t,
                types[t]["offset"][0].get<double>(), types[t]["offset"][1].get<double>(),
                types[t]["virtual_depth_range"][0].get<double>(), types[t]["virtual_depth_range"][1].get<double>());
  if (json.contains("total_covering_plane"))
    std::printf("  total covering plane: virtual depth %g\n", json["total_covering_plane"].get<double>());
  std::printf("  calibration: %s\n", json["calibration"].get<std::string>().c_str());
}

}  // namespace

void addInfoCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    FocusedOptions focused;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("info", "describe a light-field input");
  addInputOptions(*command, options->input);
  addFocusedOptions(*command, options->focused);
  command->add_flag("--json", options->json, "print a JSON object (angular, spatial, channels, ...)");
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (isFocusedInput(options->input, options->focused)) {
        LFCAM_ASSIGN_OR_RETURN(auto capture, loadFocusedInput(options->input, options->focused));
        const nlohmann::json json = focusedInfoJson(options->input.path, options->input.white, capture);
        if (options->json)
          std::printf("%s\n", json.dump(2).c_str());
        else
          printFocusedText(json);
        return {};
      }
      const bool container = looksLikeLytroContainer(options->input.path);
      LFCAM_ASSIGN_OR_RETURN(auto white, whiteNote(options->input, container));
      if (container) return printLytroInfo(options->input.path, options->json, white);
      LFCAM_ASSIGN_OR_RETURN(auto info, probeLightField(options->input.path, options->input.readOptions()));
      if (options->json) {
        nlohmann::json json = infoJson(options->input.path, info);
        if (white) json["white"] = white->json;
        std::printf("%s\n", json.dump(2).c_str());
      } else {
        printText(options->input.path, info);
        if (white) std::printf("  white: %s\n", white->text.c_str());
      }
      return {};
    };
  });
}

}  // namespace lfcam::cli
