// The simulator's lattice (camera_model.hpp) restated in LensletGrid's terms.
#include "simulate/simulated_grid.hpp"

#include <cmath>

namespace lfcam {

LensletGrid gridFromCamera(const CameraModel& camera) {
  LensletGrid grid;
  if (!camera.microlenses) return grid;
  const MicrolensArray& m = *camera.microlenses;
  // Microlens images are spaced by the lens pitch magnified by 1 + separation / F on the sensor.
  const double scale = 1.0 + m.separationMm() / camera.mainLens.imageDistanceMm();
  grid.packing = m.packing;
  grid.pitchX = m.pitchMm * scale / camera.sensor.pixelPitchMm;
  grid.pitchY = m.rowPitchMm() * scale / camera.sensor.pixelPitchMm;
  grid.rotationRad = m.rotationDeg * M_PI / 180.0;
  const auto [columns, rows] = camera.microlensCounts();
  grid.columns = columns;
  grid.rows = rows;
  // The raw is the sensor turned by 180 degrees: its microlens (i, j) is the simulator's
  // (columns - 1 - i, rows - 1 - j). The simulator's odd rows, half a pitch towards +x on the
  // sensor, lie half a pitch towards -x in the raw, so the raw's shifted rows are the others:
  // (j + rows) odd.
  grid.hexParity = m.packing == Packing::Hexagonal ? (rows & 1) : 0;
  grid.origin = camera.microlensImageCentrePx(columns - 1, rows - 1);
  if (grid.hexParity) {  // row 0 is shifted: the origin is where it would lie unshifted
    grid.origin[0] -= 0.5 * grid.pitchX * std::cos(grid.rotationRad);
    grid.origin[1] -= 0.5 * grid.pitchX * std::sin(grid.rotationRad);
  }
  return grid;
}

}  // namespace lfcam
