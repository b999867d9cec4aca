// lfcam calibrate WHITE [--metadata FILE] [--pinhole | --scene] [--bayer PATTERN] [--black-level N]
// -o grid.json: finds the microlens lattice and writes it as grid.json (docs/formats.md). WHITE is
// read as a raw (raw_io.hpp): values in DN, the black level as the file says unless given.
// lfcam calibrate --focused CAPTURE [--white W] -o calibration.xml|.json: a focused plenoptic
// capture's micro-image grid, orientation and lens types (focused_self_calibration.hpp), written
// as Raytrix's RayCalibData (or its JSON twin) for every focused command to find beside it.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/focused/focused_capture.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "raw_input.hpp"

namespace lfcam::cli {

namespace {

Status calibrateFocused(const std::string& capturePath, const std::string& white, const std::string& output) {
  const std::filesystem::path out = output;
  if (out.extension() != ".xml" && out.extension() != ".json")
    return makeError(ErrorCode::Usage, output + ": a focused calibration is written as .xml or .json");
  LFCAM_ASSIGN_OR_RETURN(
      const FocusedCapture capture,
      readFocusedCapture(capturePath,
                         {.calibration = std::filesystem::path(), .white = white, .calibrateIfNone = true}));
  if (!capture.selfCalibration)
    return makeError(ErrorCode::Usage, capturePath + ": has a calibration beside it (" +
                                           capture.calibrationPath.string() + "); move it away to calibrate anew");
  LFCAM_TRY(writeFocusedCalibration(out, capture.calibration));
  const FocusedSelfCalibration& found = *capture.selfCalibration;
  const FocusedCalibration& c = capture.calibration;
  std::printf("%s micro-images, %d x %d, diameter %.4f px, rotation %.4f deg, %s; %zu lens type%s\n",
              packingName(c.grid.packing), c.grid.columns, c.grid.rows, c.diameterPx(),
              c.grid.rotationRad * 180.0 / M_PI,
              c.orientation == MicroImageOrientation::Upright ? "upright (Galilean)" : "inverted (Keplerian)",
              c.lensTypes.size(), c.lensTypes.size() == 1 ? "" : "s");
  if (found.confidenceUpright > 0 || found.confidenceInverted > 0)
    std::printf("way up: mean depth confidence %.3f upright, %.3f inverted\n", found.confidenceUpright,
                found.confidenceInverted);
  for (const LensType& type : c.lensTypes)
    std::printf("lens type offset (%g, %g): sharp at virtual depths %.2f to %.2f\n", type.offset[0], type.offset[1],
                type.minVirtualDepth, type.maxVirtualDepth);
  std::printf("lens types' sharpness spread %.3f (one type below 0.15); per-lens fit %d centres, RMS %.3f px\n",
              found.lensTypeSpread, found.gridFit.lensletsUsed, found.gridFit.rmsResidualPx);
  return {};
}

}  // namespace

void addCalibrateCommand(CLI::App& app, Job& job) {
  struct Options {
    std::string white, metadata, bayer, output, focusedWhite;
    bool pinhole = false, scene = false, focused = false;
    std::optional<double> black;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("calibrate", "find the microlens grid in a white image; write grid.json");
  command->add_option("WHITE", options->white, "white image (PNG or TIFF, 8 or 16 bit; or a raw lfcam decodes)")
      ->required();
  command->add_option("--metadata", options->metadata,
                      "starting guess: the simulator's camera.json or a Lytro frame metadata JSON");
  auto* pinhole = command->add_flag("--pinhole", options->pinhole,
                                    "the image is a pinhole-source target: a sharp spot under each microlens");
  auto* scene = command->add_flag("--scene", options->scene, "no white image: estimate the grid from a raw scene");
  pinhole->excludes(scene);
  auto* focused = command->add_flag("--focused", options->focused,
                                    "the image is a focused plenoptic capture (Raytrix): write its calibration "
                                    "(.xml RayCalibData or .json), found from --white or from the capture itself");
  focused->excludes(pinhole)->excludes(scene);
  command->add_option("--white", options->focusedWhite, "with --focused: a white image of the same camera")
      ->needs(focused);
  command->add_option("--bayer", options->bayer, "the image is a Bayer mosaic: RGGB, BGGR, GRBG or GBRG");
  addBlackLevelOption(*command, options->black);
  command->add_option("-o,--output", options->output, "grid file to write (.json; with --focused .xml or .json)")
      ->required();
  command->callback([options, &job] {
    job = [options]() -> Status {
      if (options->focused) return calibrateFocused(options->white, options->focusedWhite, options->output);
      CalibrationOptions calibration;
      if (!options->bayer.empty()) {
        const auto filter = parseColorFilterName(options->bayer);
        if (!filter)
          return makeError(ErrorCode::Usage,
                           "--bayer: " + options->bayer + ": expected RGGB, BGGR, GRBG, GBRG or mono");
        calibration.colorFilter = *filter;
      }
      if (options->pinhole) calibration.target = CalibrationTarget::Pinhole;
      if (options->scene) calibration.target = CalibrationTarget::Scene;
      if (!options->metadata.empty()) {
        LFCAM_ASSIGN_OR_RETURN(auto hint, readLensletHint(options->metadata));
        calibration.hint = hint;
      }
      // camera.json is not consulted: --metadata says where the starting guess comes from.
      LFCAM_ASSIGN_OR_RETURN(auto raw, readRaw(options->white, {.blackLevel = options->black, .useCameraJson = false}));
      LFCAM_ASSIGN_OR_RETURN(auto grid, calibrateGrid(raw, calibration, options->white));
      LFCAM_TRY(writeGrid(options->output, grid));
      const LensletGrid& g = grid;
      std::printf("%s grid, %d x %d microlenses; pitch %.4f x %.4f px; rotation %.4f deg; origin (%.3f, %.3f) px%s\n",
                  packingName(g.packing), g.columns, g.rows, g.pitchX, g.pitchY, g.rotationRad * 180.0 / M_PI,
                  g.origin[0], g.origin[1],
                  g.packing == Packing::Hexagonal ? (g.hexParity ? ", row 0 shifted" : ", row 1 shifted") : "");
      std::printf("fit%s: %d centres found, %d used; residual RMS %.4f px, max %.4f px\n",
                  g.fit.selfCalibrated ? " (self-calibrated from the scene, microlenses with signal)" : "",
                  g.fit.lensletsFound, g.fit.lensletsUsed, g.fit.rmsResidualPx, g.fit.maxResidualPx);
      return {};
    };
  });
}

}  // namespace lfcam::cli
