// lfcam animate INPUT (--focus-pull | --orbit) -o OUT.gif|OUT.mp4: a looping animation, either the
// focus swept through the scene's depth and back, or the observer (Equation 7) moved round a
// circle on the lens; a GIF or an MP4 video by the output's extension. With --stills, OUT is a
// folder of frame_NNN.EXT images instead, as precise as --format and --bit-depth ask.
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "image_output.hpp"
#include "lfcam/render/animation.hpp"
#include "lfcam/render/focal_stack.hpp"
#include "lfcam/render/synthetic_camera.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addAnimateCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    bool focusPull = false, orbit = false, stills = false;
    std::string extension = "png", depth;
    std::string slopes;
    std::optional<double> radius;
    int frames = 24, fps = 12;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command =
      app.add_subcommand("animate", "a looping GIF or an MP4 video: a focus pull or an orbit of the observer");
  addInputOptions(*command, options->input);
  auto* pull = command->add_flag("--focus-pull", options->focusPull, "sweep the focus through the scene and back");
  auto* orbit = command->add_flag("--orbit", options->orbit, "move the observer round a circle on the lens");
  pull->excludes(orbit);
  command->add_option("--slopes", options->slopes,
                      "focus pull: FIRST:LAST slopes (default: the light field's disparity range, else -2:2)");
  command->add_option("--radius", options->radius, "orbit: radius in view steps (default: 80% of the lens)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--frames", options->frames, "frames (a focus pull goes there and back)")
      ->check(CLI::Range(2, 1000));
  command->add_option("--fps", options->fps, "frames per second")->check(CLI::Range(1, 100));
  command->add_option("-o,--output", options->output, "output .gif or .mp4 (with --stills: a folder)")->required();
  auto* stills =
      command->add_flag("--stills", options->stills, "write the frames as images frame_NNN.EXT into the -o folder");
  command->add_option("--format", options->extension, "--stills: image format of the frames")
      ->check(CLI::IsMember({"png", "tif", "exr", "jpg", "pfm"}))
      ->needs(stills);
  addBitDepthOption(*command, options->depth)->needs(stills);
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (!options->focusPull && !options->orbit)
        return makeError(ErrorCode::Usage, "animate: choose --focus-pull or --orbit");
      const auto frameName = [&](std::size_t index) {
        char name[64];
        std::snprintf(name, sizeof name, "frame_%03zu.%s", index, options->extension.c_str());
        return std::string(name);
      };
      std::optional<ImageWriteOptions> stillOptions;
      if (options->stills) {
        LFCAM_ASSIGN_OR_RETURN(
            auto checked, imageWriteOptionsFor(std::filesystem::path(options->output) / frameName(0), options->depth));
        stillOptions = checked;
      }
      std::optional<std::pair<double, double>> range;
      if (!options->slopes.empty()) {
        double a = 0, b = 0;
        char end = 0;
        if (std::sscanf(options->slopes.c_str(), "%lf:%lf%c", &a, &b, &end) != 2 || !std::isfinite(a) ||
            !std::isfinite(b))
          return makeError(ErrorCode::Usage, "--slopes: expected FIRST:LAST, got '" + options->slopes + "'");
        range = std::pair{a, b};
      }
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      std::vector<Image> frames;
      ProgressBar bar("animating");
      if (options->focusPull) {
        const double first = range ? range->first : lightField.metadata.disparityMin.value_or(-2.0);
        const double last = range ? range->second : lightField.metadata.disparityMax.value_or(2.0);
        // There and back: the sweep, then its inner frames reversed, so the loop has no jump.
        std::vector<double> slopes = evenlySpaced(first, last, options->frames / 2 + 1);
        for (int i = int(slopes.size()) - 2; i > 0; --i) slopes.push_back(slopes[i]);
        LFCAM_TRY(renderFocalStack(lightField, slopes, {}, {}, [&](int index, double, Image&& photo) -> Status {
          frames.push_back(std::move(photo));
          bar(double(index + 1) / double(slopes.size()));
          return {};
        }));
      } else {
        const double radius = options->radius.value_or(0.8 * 0.5 * (std::min(lightField.nu(), lightField.nv()) - 1));
        for (int i = 0; i < options->frames; ++i) {
          const double angle = 2 * std::numbers::pi * i / options->frames;
          LFCAM_ASSIGN_OR_RETURN(
              auto photo,
              observe(lightField, {.u = radius * std::cos(angle), .v = radius * std::sin(angle), .clampToLens = true}));
          frames.push_back(std::move(photo));
          bar(double(i + 1) / options->frames);
        }
      }
      if (!stillOptions) return writeAnimation(options->output, frames, options->fps);
      return writeFolderAtomically(options->output, [&](const std::filesystem::path& folder) -> Status {
        for (std::size_t i = 0; i < frames.size(); ++i)
          LFCAM_TRY(writeImage(folder / frameName(i), frames[i], *stillOptions));
        return {};
      });
    };
  });
}

}  // namespace lfcam::cli
