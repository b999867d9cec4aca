// calibrate: finds the microlens lattice (lenslet_grid.hpp) in a white image, a pinhole-source
// image (the paper's section 5.1: a sharp spot under each microlens) or a raw scene image.
//
// Method (docs/design.md, "Calibration"): per-CFA-phase normalisation, a 3x3 median and a
// binomial (Bayer mosaics, hot and dead pixels); a first lattice from the autocorrelation of the
// central part (or the hint); microlens centres (an iterated centroid, then the centre of
// symmetry of the microlens image) grown outwards from the centre with a lattice refit at each
// step; a least-squares fit of the lattice formula (origin, pitchX, pitchY, rotation) with
// iterative rejection of outliers (partial, vignetted or damaged microlens images).
// Threads: parallelFor over microlenses and rows.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/core/sensor_layout.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam {

enum class CalibrationTarget {
  White,    // a white (flat-field) image: a bright disc under each microlens
  Pinhole,  // a pinhole source: a small sharp spot under each microlens
  Scene,    // an ordinary raw: the grid is estimated from the raw itself
};

struct CalibrationOptions {
  // Starting guess (pitch, rotation, packing); without it the lattice is found from the image's
  // autocorrelation. offsetPx is not used. Always refined by the fit.
  std::optional<LensletHint> hint;
  CalibrationTarget target = CalibrationTarget::White;
  // A mosaic: each 2x2 phase is normalised to the same mean before anything else. The pattern
  // itself does not matter; Mono skips the step.
  ColorFilter colorFilter = ColorFilter::Mono;
  // Subtracted from every value first (a raw's black level, in the image's units).
  double blackLevel = 0;
  // The lattice has five parameters: on a larger grid the sub-pixel centres (the costly step) are
  // measured on an even subset of about this many microlenses, spread over the whole image, and
  // the fit report counts that subset; the extent still comes from every microlens. 0: all.
  int fitCentres = 30000;
};

// One measured microlens centre, in the fitted grid's (i, j).
struct DetectedCentre {
  int i = 0, j = 0;
  double x = 0, y = 0;    // pixels
  double residualPx = 0;  // distance to the fitted lattice
  bool inlier = false;
};

struct Calibration {
  LensletGrid grid;
  std::vector<DetectedCentre> centres;
};

// The image: one channel (more are averaged), any scale. The grid's columns x rows: the index
// rectangle around the microlenses whose images were found inside the image on the fitted lattice.
// Errors: Usage for an empty image or a bad hint, Format when no lattice can be found (messages
// start with `where`).
Result<Calibration> calibrateGridDetailed(const Image& image, const CalibrationOptions& options,
                                          const std::string& where = "image");
Result<LensletGrid> calibrateGrid(const Image& image, const CalibrationOptions& options,
                                  const std::string& where = "image");
// The same for a raw: its colour filter, black level and lenslet hint fill in what `options`
// leaves unset (an options hint wins).
Result<LensletGrid> calibrateGrid(const RawImage& raw, CalibrationOptions options, const std::string& where = "raw");

// A starting guess from a metadata file: the simulator's camera.json (its "lattice_px") or a Lytro
// frame metadata JSON (devices.mla: lensPitch, rotation, sensorOffset; devices.sensor.pixelPitch).
Result<LensletHint> readLensletHint(const std::filesystem::path& path);

}  // namespace lfcam

namespace lfcam {

// The steps on their own, for tests.

// 3x3 median of a one-channel image (borders: the window clipped to the image): hot and dead
// pixels go, the centre of a centrally symmetric spot stays.
Image median3x3(const Image& image);

}  // namespace lfcam
