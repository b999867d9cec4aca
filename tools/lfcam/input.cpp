#include "commands.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addInputOptions(CLI::App& command, InputOptions& input) {
  command.add_option("INPUT", input.path,
                     "light field: .lf.h5 file, HCI or RR_CC view folder, or lenslet image")
      ->required();
  command.add_option("--lenslet-views", input.lensletViews,
                     "views across each microlens of a lenslet image that does not say so itself")
      ->check(CLI::Range(1, 1024));
}

Result<LightField> loadInput(const InputOptions& input) {
  ProgressBar bar("reading " + input.path);
  return readLightField(input.path, LightFieldReadOptions{.lensletViews = input.lensletViews},
                        [&](double fraction) { bar(fraction); });
}

}  // namespace lfcam::cli
