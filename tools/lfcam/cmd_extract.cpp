// lfcam extract FILE -o DIR: everything in a Lytro container as ordinary files (refocus-stack
// JPEGs, H.264 streams, depth maps as PFM and PNG, metadata as JSON, a raw frame as TIFF).
#include <memory>

#include "commands.hpp"
#include "raw_io/lytro_contents.hpp"

namespace lfcam::cli {

void addExtractCommand(CLI::App& app, Job& job) {
  struct Options {
    std::string input, output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("extract", "write the images, depth maps and metadata of a Lytro file");
  command->add_option("input", options->input, "Lytro container (.lfp, .lfr)")->required();
  command->add_option("-o,--output", options->output, "output folder (index.json lists what was written)")->required();
  command->callback([options, &job] {
    job = [options]() -> Status {
      LFCAM_ASSIGN_OR_RETURN(auto container, readLytroContainer(options->input));
      return extractLytroContainer(container, options->output, options->input);
    };
  });
}

}  // namespace lfcam::cli
