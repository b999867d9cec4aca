// lfcam stack INPUT (--slopes A:B:N | --alphas A:B:N) -o DIR: a focal stack, one photograph per
// focus depth (slice_000.png, ...), and stack.json naming the slope (and alpha) of each.
#include <cstdio>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "image_output.hpp"
#include "lfcam/atomic_file.hpp"
#include "lfcam/focal_stack.hpp"
#include "lfcam/parallel.hpp"
#include "progress_bar.hpp"
#include "render_cli.hpp"

namespace lfcam::cli {

namespace {
// Slices rendered but not yet written, each one photograph's memory.
constexpr std::size_t kSlicesWaitingToBeWritten = 4;
}  // namespace

void addStackCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::string slopes, alphas;
    CameraOptions camera;
    std::string extension = "png", depth;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("stack", "a focal stack: one refocused photograph per depth");
  addInputOptions(*command, options->input);
  auto* slopes = command->add_option("--slopes", options->slopes, "FIRST:LAST:COUNT slopes, pixels per view step");
  auto* alphas = command->add_option("--alphas", options->alphas, "FIRST:LAST:COUNT film depths (needs optics)");
  slopes->excludes(alphas);
  addCameraOptions(*command, options->camera);
  command->add_option("--format", options->extension, "image format of the slices")
      ->check(CLI::IsMember({"png", "tif", "exr", "jpg", "pfm"}));
  addBitDepthOption(*command, options->depth);
  command->add_option("-o,--output", options->output, "output folder")->required();
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (options->slopes.empty() == options->alphas.empty())
        return makeError(ErrorCode::Usage, "stack: give the depths with --slopes or --alphas");
      LFCAM_ASSIGN_OR_RETURN(auto values, parseRange(options->slopes.empty() ? options->alphas : options->slopes,
                                                     options->slopes.empty() ? "--alphas" : "--slopes"));
      const auto sliceName = [&](int index) {
        char name[64];
        std::snprintf(name, sizeof name, "slice_%03d.%s", index, options->extension.c_str());
        return std::string(name);
      };
      LFCAM_ASSIGN_OR_RETURN(
          auto writeOptions,
          imageWriteOptionsFor(std::filesystem::path(options->output) / sliceName(0), options->depth));
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      LFCAM_ASSIGN_OR_RETURN(auto camera, cameraFrom(options->camera, lightField, options->input.path));
      std::vector<double> slopeValues = values;
      const auto& optics = lightField.metadata.optics;
      if (!options->alphas.empty())
        for (double& value : slopeValues) {
          LFCAM_ASSIGN_OR_RETURN(value, slopeFromAlpha(lightField, value, options->input.path));
        }
      ProgressBar bar("focal stack");
      return writeFolderAtomically(options->output, [&](const std::filesystem::path& folder) -> Status {
        nlohmann::json slices = nlohmann::json::array();
        // Each slice is encoded and written while the next is rendered; a few wait at most.
        BackgroundTasks writes(kSlicesWaitingToBeWritten);
        LFCAM_TRY(renderPhotos(lightField, camera, slopeValues, [&](int index, double slope, Image&& photo) -> Status {
          const std::string name = sliceName(index);
          nlohmann::json slice{{"file", name}, {"slope", slope}};
          if (optics) slice["alpha"] = optics->alphaFromSlope(slope);
          slices.push_back(slice);
          bar(double(index + 1) / double(slopeValues.size()));
          auto shared = std::make_shared<Image>(std::move(photo));
          return writes.add([&, shared, name] { return writeImage(folder / name, *shared, writeOptions); });
        }));
        LFCAM_TRY(writes.wait());
        std::ofstream out(folder / "stack.json");
        out << nlohmann::json{{"slices", slices}}.dump(2) << "\n";
        if (!out) return makeError(ErrorCode::Io, (folder / "stack.json").string() + ": cannot write");
        return {};
      });
    };
  });
}

}  // namespace lfcam::cli
