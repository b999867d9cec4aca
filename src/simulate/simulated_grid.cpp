// The simulator's lattice (camera_model.hpp) restated in LensletGrid's terms.
#include "lfcam/simulated_grid.hpp"

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
  grid.origin = camera.microlensImageCentrePx(0, 0);
  const auto [columns, rows] = camera.microlensCounts();
  grid.columns = columns;
  grid.rows = rows;
  grid.hexParity = 0;
  return grid;
}

}  // namespace lfcam
