// lfcam denoise INPUT -o OUT.lf.h5 [--depth-range A:B]: the light field through a linear 4D
// frequency-domain filter that keeps the surfaces of slopes A to B and removes most sensor noise
// (denoise.hpp: a hyperfan passband, a plane when A = B).
#include <cmath>
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "lfcam/render/denoise.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

namespace {

// "A:B" -> two finite slopes with A <= B.
Result<std::pair<double, double>> parseDepthRange(const std::string& text) {
  double a = 0, b = 0;
  char end = 0;
  if (std::sscanf(text.c_str(), "%lf:%lf%c", &a, &b, &end) != 2 || !std::isfinite(a) || !std::isfinite(b))
    return makeError(ErrorCode::Usage, "--depth-range: expected two slopes as A:B, got '" + text + "'");
  if (a > b)
    return makeError(ErrorCode::Usage, "--depth-range: A must not exceed B (slopes, nearest last), got '" + text + "'");
  return std::pair{a, b};
}

}  // namespace

void addDenoiseCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    std::string output, range;
    std::optional<double> bandwidth;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "denoise", "remove noise with a 4D frequency-domain filter that keeps a range of depths (hyperfan)");
  addInputOptions(*command, options->input);
  command->add_option("-o,--output", options->output, "output light field: NAME.lf.h5 (or a folder, as convert)")
      ->required();
  command->add_option("--depth-range", options->range,
                      "A:B slopes (pixels per view step) to keep; A = B keeps one depth (a planar passband). "
                      "Default: the light field's stated disparity range, else -2:2");
  command->add_option("--bandwidth", options->bandwidth,
                      "width of the passband's roll-off, cycles per view step (default 0.11): narrower removes more "
                      "noise and more of what is not a plain surface");
  command->callback([options, &job] {
    job = [options]() -> Status {
      std::optional<std::pair<double, double>> range;
      if (!options->range.empty()) {
        LFCAM_ASSIGN_OR_RETURN(range, parseDepthRange(options->range));
      }
      if (options->bandwidth && !(*options->bandwidth > 0 && *options->bandwidth <= 0.5))
        return makeError(ErrorCode::Usage, "--bandwidth: must lie in (0, 0.5] cycles per view step");
      LFCAM_ASSIGN_OR_RETURN(auto lightField, loadInput(options->input));
      DenoiseOptions denoiseOptions = defaultDenoiseOptions(lightField);
      if (range) denoiseOptions.slopeMin = range->first, denoiseOptions.slopeMax = range->second;
      if (options->bandwidth) denoiseOptions.bandwidth = *options->bandwidth;
      auto filtered = denoise(lightField, denoiseOptions);
      if (!filtered) return makeError(filtered.error().code, options->input.path + ": " + filtered.error().message);
      ProgressBar bar("writing " + options->output);
      return writeLightField(options->output, *filtered, {}, [&](double f) { bar(f); });
    };
  });
}

}  // namespace lfcam::cli
