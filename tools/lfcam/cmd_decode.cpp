// lfcam decode RAW [--white W | --whites whites.json [--any-camera]] [--dark D] [--black-level N] [--grid grid.json]
// [--bayer P] [--demosaic M]
//                  [--sampling S] [--views N] -o OUT.lf.h5: a raw lenslet image -> L(u, v, s, t).
#include <memory>

#include "commands.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "raw_input.hpp"

namespace lfcam::cli {

void addDecodeCommand(CLI::App& app, Job& job) {
  struct Options {
    RawFiles input;
    std::string bayer, output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("decode", "decode a raw lenslet image into a light field");
  command->add_option("RAW", options->input.raw, "raw lenslet image: PNG/TIFF, Lytro .lfp/.lfr, camera raw")
      ->required();
  command->add_option("--white", options->input.white, "white image of the same camera (devignetting, weights)");
  command->add_option("--dark", options->input.dark, "dark frame, subtracted instead of the black level");
  addBlackLevelOption(*command, options->input.blackLevel);
  command->add_option("--grid", options->input.grid,
                      "grid.json from lfcam calibrate (default: calibrate the white image, without one the raw)");
  addWhitesOptions(*command, options->input.whites, options->input.anyCamera);
  command->add_option("--bayer", options->bayer, "colour filter of a PNG/TIFF raw: RGGB, BGGR, GRBG, GBRG or mono");
  addDecodeMethodOptions(*command, options->input.decode);
  command->add_option("--views", options->input.decode.views, "views across (default: the microlens pitch, rounded)")
      ->check(CLI::Range(1, 256));
  command->add_option("-o,--output", options->output, "output light field (.lf.h5)")->required();
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (!options->bayer.empty()) {
        LFCAM_ASSIGN_OR_RETURN(auto filter, parseBayerOption(options->bayer));
        options->input.bayer = filter;
      }
      LFCAM_ASSIGN_OR_RETURN(auto lf, decodeRawInput(options->input));
      return writeLightField(options->output, lf);
    };
  });
}

}  // namespace lfcam::cli
