// LensletGrid: where the microlens images lie on the sensor, as calibration finds them.
//
// Pixel coordinates as in image.hpp (pixel (x, y) covers [x, x+1) x [y, y+1)). Microlens (i, j),
// i in [0, columns), j in [0, rows), has its image centre at
//   centre(i, j) = origin + R(rotationRad) * (a, b)
//   square:    a = i * pitchX,                        b = j * pitchY
//   hexagonal: a = (i + (shifted(j) ? 0.5 : 0)) * pitchX, b = j * pitchY
// with shifted(j) = ((j + hexParity) odd), R rotating x towards y. For an ideal hexagonal
// array pitchY = pitchX * sqrt(3) / 2; both are fitted. A grid may add a smooth warp: offsets in
// pixels on a coarse mesh over (i, j), interpolated bilinearly and added to centre(i, j), for an
// array (or an optical path) that is not quite a lattice (GridWarp).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "lfcam/core/result.hpp"
#include "lfcam/core/sensor_layout.hpp"

namespace lfcam {

struct GridFitReport {
  int lensletsFound = 0;     // centres detected in the image
  int lensletsUsed = 0;      // inliers of the lattice fit
  double rmsResidualPx = 0;  // of the inliers' detected centres against the lattice
  double maxResidualPx = 0;
  // Estimated from a scene (CalibrationTarget::Scene): no white image; residuals of the
  // microlenses with signal only.
  bool selfCalibrated = false;
};

// Control point (p, q), p in [0, columns), q in [0, rows), sits at microlens
// (p (grid.columns - 1) / (columns - 1), q (grid.rows - 1) / (rows - 1)); offsets[q * columns + p].
struct GridWarp {
  int columns = 0, rows = 0;  // 0: no warp; else both >= 2
  std::vector<std::array<double, 2>> offsets;
};

struct LensletGrid {
  Packing packing = Packing::Square;
  double pitchX = 0, pitchY = 0;  // pixels
  double rotationRad = 0;
  std::array<double, 2> origin{0, 0};  // centre of microlens (0, 0), pixels
  int columns = 0, rows = 0;
  int hexParity = 0;  // 0 or 1, see above
  GridWarp warp;
  GridFitReport fit;

  std::array<double, 2> centre(int i, int j) const;         // with the warp
  std::array<double, 2> latticeCentre(int i, int j) const;  // without it
};

// grid.json (docs/formats.md).
Result<LensletGrid> readGrid(const std::filesystem::path& path);
Status writeGrid(const std::filesystem::path& path, const LensletGrid& grid);

}  // namespace lfcam
