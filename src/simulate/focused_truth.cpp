#include "lfcam/simulate/focused_truth.hpp"

#include <cmath>
#include <limits>

#include "core/parallel.hpp"
#include "simulate/simulated_grid.hpp"
#include "simulate/tracing.hpp"

namespace lfcam {

namespace {

// +1 when the main lens's image of the scene lies in front of the microlenses (Keplerian).
double keplerian(const MicrolensArray& m) { return m.focalLengthOf(0, 0) < m.separationMm() ? 1.0 : -1.0; }

FocusedOptics opticsOf(const CameraModel& camera) {
  return {.mainFocalLengthMm = camera.mainLens.focalLengthMm,
          .mainLensToMicrolensesMm = camera.mainLens.imageDistanceMm(),
          .microlensesToSensorMm = camera.microlenses->separationMm()};
}

MicroImageOrientation orientationOf(const MicrolensArray& m) {
  return keplerian(m) > 0 ? MicroImageOrientation::Inverted : MicroImageOrientation::Upright;
}

double imageInFront(const CameraModel& camera, double v) {
  return mainLensImageInFrontMm(opticsOf(camera), orientationOf(*camera.microlenses), v);
}

constexpr double kSqrt3 = 1.7320508075688772;

// Where microlens `f` images a point: the sensor distance b' of its sharp image, for a point of the
// main lens's image `a` mm in front of the microlenses (negative: behind, a virtual object).
double sharpImageDistance(double f, double a) { return 1.0 / (1.0 / f - 1.0 / a); }

// The virtual depths a microlens of focal length f images with a blur of at most `blurPx` pixels.
std::array<double, 2> sharpVirtualDepths(const CameraModel& camera, double f, double blurPx) {
  const MicrolensArray& m = *camera.microlenses;
  const double b = m.separationMm();
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (double v = 0.5; v < 1000; v *= 1.002) {  // steps of 0.2 %
    const double a = imageInFront(camera, v);
    const double image = sharpImageDistance(f, a);
    const double blurMm = image > 0 ? m.pitchMm * std::abs(b - image) / image : std::numeric_limits<double>::infinity();
    if (blurMm <= blurPx * camera.sensor.pixelPitchMm) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  return {lo, hi};
}

}  // namespace

double focusedVirtualDepth(const CameraModel& camera, double depthMm) {
  const MicrolensArray& m = *camera.microlenses;
  const double f = camera.mainLens.focalLengthMm, F = camera.mainLens.imageDistanceMm(), b = m.separationMm();
  const double imageDistance = std::isfinite(depthMm) && depthMm > f ? f * depthMm / (depthMm - f) : f;
  const double a = F - imageDistance;
  return keplerian(m) * (a / b) * (F + b) / (F - a);
}

double depthOfFocusedVirtualDepth(const CameraModel& camera, double virtualDepth) {
  return distanceOfVirtualDepth(opticsOf(camera), orientationOf(*camera.microlenses), virtualDepth);
}

Result<FocusedCalibration> focusedCalibrationFromCamera(const CameraModel& camera) {
  if (!camera.microlenses) return makeError(ErrorCode::Usage, "focused calibration: the camera has no microlens array");
  const MicrolensArray& m = *camera.microlenses;
  const double b = m.separationMm();
  for (int type = 0; type < m.lensTypes(); ++type)
    if (std::abs(m.focalLengthOf(type, 0) - b) < 1e-9 * b)
      return makeError(ErrorCode::Usage,
                       "focused calibration: the sensor is at the microlenses' focus (a plenoptic 1.0 camera)");
  FocusedCalibration calibration;
  calibration.grid = gridFromCamera(camera);
  calibration.imageWidth = camera.sensor.width;
  calibration.imageHeight = camera.sensor.height;
  LensletGrid& grid = calibration.grid;
  // The reference lens: the one nearest the image's centre.
  double best = std::numeric_limits<double>::infinity();
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      const auto c = grid.latticeCentre(i, j);
      const double d = std::hypot(c[0] - 0.5 * camera.sensor.width, c[1] - 0.5 * camera.sensor.height);
      if (d < best) {
        best = d;
        calibration.referenceLens = {i, j};
      }
    }
  const double d = grid.pitchX;
  const double imageRadius = 0.5 * std::min(d, camera.microlensImageDiameterPx());
  calibration.borderPx = std::max(0.5, 0.5 * d - imageRadius + 0.5);
  const double usable = 0.5 * d - calibration.borderPx;
  calibration.orientation = orientationOf(m);
  calibration.optics = opticsOf(camera);
  // Raw lens (i, j) is the simulator's (columns - 1 - i, rows - 1 - j): the raw is turned by 180
  // degrees. Raytrix's types are named by offsets (0, 0), (1, 0) and (-1, 0): a type's lenses lie
  // at the reference lens less its offset (focused_calibration.hpp).
  const auto [i0, j0] = calibration.referenceLens;
  auto simulatorFocalLength = [&](int i, int j) { return m.focalLengthOf(grid.columns - 1 - i, grid.rows - 1 - j); };
  const int offsets[3] = {0, 1, -1};
  for (int t = 0; t < m.lensTypes(); ++t) {
    LensType type;
    type.offset = {double(offsets[t]), 0};
    const auto range = sharpVirtualDepths(camera, simulatorFocalLength(i0 - offsets[t], j0), 2.0);
    type.minVirtualDepth = range[0];
    type.maxVirtualDepth = std::max(range[0], range[1]);
    calibration.lensTypes.push_back(type);
  }
  // Every point seen by a micro-image of each type (three types: the same-type lenses' cells have a
  // circumradius of D), or by one (the lattice's own cells: D / sqrt(3) hexagonal, D / sqrt(2) square).
  const double cover = m.lensTypes() == 3 ? d : (m.packing == Packing::Hexagonal ? d / kSqrt3 : d / std::sqrt(2.0));
  calibration.totalCoveringPlane = cover / usable;
  return calibration;
}

Result<FocusedTruth> focusedTruth(const Scene& scene, const CameraModel& camera, const FocusedPhotoFrame& frame,
                                  int boxSamples) {
  if (!camera.microlenses) return makeError(ErrorCode::Usage, "focused truth: the camera has no microlens array");
  const simulate_detail::PreparedScene prepared(scene, camera);
  const double F = camera.mainLens.imageDistanceMm(), b = camera.microlenses->separationMm();
  const double pixel = camera.sensor.pixelPitchMm, width = camera.sensor.width, height = camera.sensor.height;
  const int n = std::max(1, boxSamples);
  FocusedTruth truth{Image(frame.width, frame.height, 3), Image(frame.width, frame.height, 1)};
  // An image point -> the microlens plane (the raw is the sensor turned by 180 degrees; the sensor
  // is F + b from the main lens) -> the main lens's central ray through it.
  auto trace = [&](double x, double y) {
    const auto point = frame.imagePoint(x, y);
    const double scale = pixel * F / (F + b);
    return prepared.traceThroughLens(0, 0, (0.5 * width - point[0]) * scale, (0.5 * height - point[1]) * scale);
  };
  parallelFor(0, std::size_t(frame.height), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < frame.width; ++x) {
        double sum[3] = {0, 0, 0};
        for (int sy = 0; sy < n; ++sy)
          for (int sx = 0; sx < n; ++sx) {
            const auto hit = trace(x + (sx + 0.5) / n, double(y) + (sy + 0.5) / n);
            for (int c = 0; c < 3; ++c) sum[c] += hit.radiance[c];
          }
        for (int c = 0; c < 3; ++c) truth.allInFocus.at(x, int(y), c) = float(sum[c] / (n * n));
        truth.virtualDepth.at(x, int(y), 0) = float(focusedVirtualDepth(camera, trace(x + 0.5, y + 0.5).depth));
      }
  });
  return truth;
}

}  // namespace lfcam
