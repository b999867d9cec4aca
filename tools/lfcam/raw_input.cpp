#include "raw_input.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <utility>

#include "lfcam/raw_io/raw_io.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

void addDecodeMethodOptions(CLI::App& command, DecodeOptions& decode) {
  command.add_option("--demosaic", decode.demosaic, "mhc (default), ha (Hamilton-Adams), lenslet or lightfield")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, DemosaicMethod>{{"mhc", DemosaicMethod::MalvarHeCutler},
                                                {"ha", DemosaicMethod::HamiltonAdams},
                                                {"lenslet", DemosaicMethod::LensletAware},
                                                {"lightfield", DemosaicMethod::LightFieldAware}}));
  command.add_option("--sampling", decode.sampling, "subpixel (default) or integral (the paper's)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, Sampling>{{"subpixel", Sampling::SubPixel}, {"integral", Sampling::IntegralPitch}}));
}

void addBlackLevelOption(CLI::App& command, std::optional<double>& blackLevel) {
  command
      .add_option("--black-level", blackLevel,
                  "black level (camera offset) in DN of the raw file, e.g. 64 of a 16-bit PNG/TIFF; default: "
                  "what the file says (camera.json, TIFF BlackLevel tag, camera raw), else 0; not used when a "
                  "--dark frame is given (it wins)")
      ->check(CLI::Validator(
          [](const std::string& text) {
            char* end = nullptr;
            const double value = std::strtod(text.c_str(), &end);
            return *end == 0 && value >= 0 && std::isfinite(value)
                       ? std::string()
                       : "expected a number of DN of at least 0, got " + text;
          },
          "DN"));
}

void addWhitesOptions(CLI::App& command, std::string& whites, bool& anyCamera) {
  command.add_option("--whites", whites,
                     "white-image database from lfcam whites index: the white of RAW's camera nearest its zoom and "
                     "focus steps, with its grid (instead of --white and --grid)");
  command.add_flag("--any-camera", anyCamera, "with --whites: choose among every camera's whites, not only RAW's");
}

Result<ColorFilter> parseBayerOption(const std::string& text) {
  if (auto filter = parseColorFilterName(text)) return *filter;
  return makeError(ErrorCode::Usage, "--bayer: " + text + " is not one of RGGB, BGGR, GRBG, GBRG, mono");
}

Result<LightField> decodeRawInput(RawFiles files) {
  ProgressBar bar("decoding " + files.raw);
  files.onWhiteChosen = [](const std::string& reason) { std::fprintf(stderr, "white: %s\n", reason.c_str()); };
  return decodeRawFiles(std::move(files), [&](double fraction) { bar(fraction); });
}

}  // namespace lfcam::cli
