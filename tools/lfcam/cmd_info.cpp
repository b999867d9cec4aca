// lfcam info INPUT [--json]: what a light-field input is, without reading its samples when the
// format allows.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
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

}  // namespace

void addInfoCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("info", "describe a light-field input");
  addInputOptions(*command, options->input);
  command->add_flag("--json", options->json, "print a JSON object (angular, spatial, channels, ...)");
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (looksLikeLytroContainer(options->input.path)) return printLytroInfo(options->input.path, options->json);
      LFCAM_ASSIGN_OR_RETURN(auto info, probeLightField(options->input.path, options->input.readOptions()));
      if (options->json)
        std::printf("%s\n", infoJson(options->input.path, info).dump(2).c_str());
      else
        printText(options->input.path, info);
      return {};
    };
  });
}

}  // namespace lfcam::cli
