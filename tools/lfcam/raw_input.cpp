#include "raw_input.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <tuple>

#include "lfcam/calibrate.hpp"
#include "lfcam/raw_io.hpp"
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

Result<ColorFilter> parseBayerOption(const std::string& text) {
  if (auto filter = parseColorFilterName(text)) return *filter;
  return makeError(ErrorCode::Usage, "--bayer: " + text + " is not one of RGGB, BGGR, GRBG, GBRG, mono");
}

Result<LightField> decodeRawInput(RawDecodeInput input) {
  ProgressBar bar("decoding " + input.raw);
  RawReadOptions readOptions;
  readOptions.colorFilter = input.bayer;
  // A dark frame is subtracted instead of any black level, so a given level is then not used.
  if (input.dark.empty()) readOptions.blackLevel = input.blackLevel;
  LFCAM_ASSIGN_OR_RETURN(auto raw, readRaw(input.raw, readOptions));
  bar(0.1);
  RawImage dark, white;
  if (!input.dark.empty()) {
    LFCAM_ASSIGN_OR_RETURN(auto read, readRaw(input.dark, readOptions));
    dark = std::move(read);
    input.decode.dark = &dark;
  }
  if (!input.white.empty()) {
    LFCAM_ASSIGN_OR_RETURN(auto read, readRaw(input.white, readOptions));
    white = std::move(read);
    input.decode.white = &white;
  }
  // Checked here as well as in decodeLightField, so that the message names the file that is wrong.
  for (const auto& [file, image, what] :
       {std::tuple{&input.dark, &dark, "dark frame"}, std::tuple{&input.white, &white, "white image"}}) {
    const Image& mosaic = image->mosaic;
    if (file->empty() || (mosaic.width() == raw.mosaic.width() && mosaic.height() == raw.mosaic.height())) continue;
    return makeError(ErrorCode::Usage, *file + ": " + what + " of " + std::to_string(mosaic.width()) + "x" +
                                           std::to_string(mosaic.height()) + " pixels does not match the raw's " +
                                           std::to_string(raw.mosaic.width()) + "x" +
                                           std::to_string(raw.mosaic.height()) + " (" + input.raw + ")");
  }
  bar(0.2);
  LensletGrid grid;
  if (!input.grid.empty()) {
    LFCAM_ASSIGN_OR_RETURN(auto read, readGrid(input.grid));
    grid = read;
  } else {
    if (input.white.empty())
      return makeError(ErrorCode::Usage, input.raw + ": decoding needs --grid or a --white image to calibrate from");
    LFCAM_ASSIGN_OR_RETURN(auto calibrated, calibrateGrid(white, CalibrationOptions{}, input.white));
    grid = calibrated;
  }
  bar(0.4);
  if (!input.decode.optics) input.decode.optics = raw.optics;
  auto lf = decodeLightField(raw, grid, input.decode);
  if (!lf) return makeError(lf.error().code, input.raw + ": " + lf.error().message);
  bar(1.0);
  return lf;
}

}  // namespace lfcam::cli
