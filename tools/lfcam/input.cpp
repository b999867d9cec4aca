#include "commands.hpp"
#include "progress_bar.hpp"
#include "raw_input.hpp"

namespace lfcam::cli {

void addInputOptions(CLI::App& command, InputOptions& input) {
  command.add_option("INPUT", input.path, "light field: .lf.h5 file, HCI or RR_CC view folder, or lenslet image")
      ->required();
  command
      .add_option("--lenslet-views", input.lensletViews,
                  "views across each microlens of a lenslet image that does not say so itself")
      ->check(CLI::Range(1, 1024));
  command
      .add_option("--view-order", input.viewOrder,
                  "in NAME_AA_BB.png view folders, which number is the row (default: auto, from the parallax)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, ViewNumberOrder>{{"auto", ViewNumberOrder::Auto},
                                                 {"row-first", ViewNumberOrder::RowFirst},
                                                 {"column-first", ViewNumberOrder::ColumnFirst}}));
  command.add_option("--white", input.white, "INPUT is a raw lenslet image: its white image (decoded on the way)");
  command.add_option("--dark", input.dark, "with --white: dark frame of the raw");
  command.add_option("--grid", input.grid, "with --white: grid.json (default: calibrated from the white image)");
  addWhitesOptions(command, input.whites, input.anyCamera);
  addBlackLevelOption(command, input.blackLevel);
  addDecodeMethodOptions(command, input.decode);
}

Result<LightField> loadInput(const InputOptions& input) {
  if (input.decodesRaw())
    return decodeRawInput({.raw = input.path,
                           .white = input.white,
                           .dark = input.dark,
                           .grid = input.grid,
                           .whites = input.whites,
                           .anyCamera = input.anyCamera,
                           .blackLevel = input.blackLevel,
                           .decode = input.decode});
  if (input.blackLevel)
    return makeError(ErrorCode::Usage,
                     input.path + ": --black-level applies to a raw decoded on the way (with --white or --whites)");
  ProgressBar bar("reading " + input.path);
  return readLightField(input.path, input.readOptions(), [&](double fraction) { bar(fraction); });
}

}  // namespace lfcam::cli
