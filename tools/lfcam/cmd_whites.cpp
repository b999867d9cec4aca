// lfcam whites index CALDATA... -o whites.json: a white-image database of Lytro calibration data or
// of PNG/TIFF whites with side-cars, each white calibrated once (white_database.hpp); `decode
// --whites` and every command that decodes on the way then choose from it.
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "lfcam/calibrate/white_database.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addWhitesCommand(CLI::App& app, Job& job) {
  struct Options {
    std::vector<std::string> sources;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("whites", "a database of a camera's white images, one per zoom and focus");
  command->require_subcommand(1);
  CLI::App* index = command->add_subcommand(
      "index", "index white images: calibrate each once, record its camera, zoom and focus steps");
  index
      ->add_option("CALDATA", options->sources,
                   "folders or files: Lytro MOD_*.RAW + .TXT, caldata-*.tar, backup volumes (data.C.*), white "
                   ".LFR/.LFP, PNG/TIFF whites with a side-car .json (serial, zoom_step, focus_step, exposure_s)")
      ->required();
  index->add_option("-o,--output", options->output, "the index to write (.json); its cache beside it (.cache/)")
      ->required();
  index->callback([options, &job] {
    job = [options]() -> Status {
      std::vector<std::filesystem::path> sources(options->sources.begin(), options->sources.end());
      ProgressBar bar("calibrating white images");
      LFCAM_ASSIGN_OR_RETURN(auto database, indexWhites(
                                                sources, options->output, [&](double fraction) { bar(fraction); },
                                                [](const std::string& line, bool passedOver) {
                                                  if (passedOver)
                                                    std::fprintf(stderr, "lfcam: warning: %s\n", line.c_str());
                                                  else
                                                    std::printf("%s\n", line.c_str());
                                                }));
      std::printf("%s: %zu whites (%s)\n", options->output.c_str(), database.whites.size(), database.madeBy.c_str());
      return {};
    };
  });
}

}  // namespace lfcam::cli
