// Decoding from files (decode_files.hpp).
#include "lfcam/decode/decode_files.hpp"

#include <tuple>
#include <utility>

#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/calibrate/white_database.hpp"
#include "lfcam/raw_io/raw_io.hpp"

namespace lfcam {

Result<LightField> decodeRawFiles(RawFiles input, const ProgressCallback& progress) {
  const auto bar = [&](double fraction) {
    if (progress) progress(fraction);
  };
  RawReadOptions readOptions;
  readOptions.colorFilter = input.bayer;
  // A dark frame is subtracted instead of any black level, so a given level is then not used.
  if (input.dark.empty()) readOptions.blackLevel = input.blackLevel;
  LFCAM_ASSIGN_OR_RETURN(auto raw, readRaw(input.raw, readOptions));
  std::string chosen;  // the database's white, for the light field's metadata
  if (!input.whites.empty()) {
    if (!input.white.empty() || !input.grid.empty())
      return makeError(ErrorCode::Usage, input.whites +
                                             ": a white-image database chooses the white and its grid: "
                                             "give it or --white/--grid, not both");
    LFCAM_ASSIGN_OR_RETURN(auto choice, chooseWhite(input.whites, raw, input.anyCamera, input.raw));
    if (input.onWhiteChosen) input.onWhiteChosen(choice.reason);
    input.white = choice.white.white.string();
    input.grid = choice.white.grid.string();
    chosen = "; white " + choice.white.name + " from " + input.whites;
  }
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
  } else if (!input.white.empty()) {
    LFCAM_ASSIGN_OR_RETURN(auto calibrated, calibrateGrid(white, CalibrationOptions{}, input.white));
    grid = calibrated;
  } else {
    // No white image: the grid from the capture itself (grid.fit says so).
    LFCAM_ASSIGN_OR_RETURN(auto calibrated, calibrateGrid(raw, {.target = CalibrationTarget::Scene}, input.raw));
    grid = calibrated;
  }
  bar(0.4);
  if (!input.decode.optics) input.decode.optics = raw.optics;
  auto lf = decodeLightField(raw, grid, input.decode);
  if (!lf) return makeError(lf.error().code, input.raw + ": " + lf.error().message);
  lf->metadata.source += chosen;
  bar(1.0);
  return lf;
}

}  // namespace lfcam
