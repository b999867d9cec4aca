// The microlens lattice as simulated matches the lattice camera.json states (square and
// hexagonal, rotated, offset), and a misplaced sensor blurs the spots of a pinhole main lens
// (sections 3.1 and 5.1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lfcam/simulate/simulate.hpp"

namespace lfcam {
namespace {

CameraModel latticeCamera(Packing packing) {
  CameraModel camera = CameraModel::paperPrototype(150, 150);
  camera.microlenses->pitchMm = 14 * 0.009;
  camera.microlenses->focalLengthMm = 4 * camera.microlenses->pitchMm;
  camera.microlenses->packing = packing;
  camera.microlenses->rotationDeg = 3;
  camera.microlenses->offsetMm = {0.02, -0.011};
  camera.mainLens.setImageSideFNumber(8);  // separate discs of 7 px
  camera.sensor.noise = false;
  camera.sensor.colorFilter = ColorFilter::Mono;
  return camera;
}

struct Spot {
  double x = 0, y = 0, rms = 0, light = 0;
};

// Centroid and RMS radius of the light within `radius` px of (cx, cy).
Spot measureSpot(const Image& image, double cx, double cy, double radius) {
  Spot spot;
  double sx = 0, sy = 0, sxx = 0;
  for (int y = int(cy - radius) - 1; y <= int(cy + radius) + 1; ++y)
    for (int x = int(cx - radius) - 1; x <= int(cx + radius) + 1; ++x) {
      if (x < 0 || y < 0 || x >= image.width() || y >= image.height()) continue;
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
      if (dx * dx + dy * dy > radius * radius) continue;
      const double v = image.at(x, y, 0);
      spot.light += v;
      sx += v * (x + 0.5);
      sy += v * (y + 0.5);
      sxx += v * (dx * dx + dy * dy);
    }
  spot.x = sx / spot.light;
  spot.y = sy / spot.light;
  spot.rms = std::sqrt(sxx / spot.light);
  return spot;
}

TEST(SimulateLattice, WhiteImageCentresAreTheStatedLattice) {
  for (Packing packing : {Packing::Square, Packing::Hexagonal}) {
    SCOPED_TRACE(packingName(packing));
    const CameraModel camera = latticeCamera(packing);
    const SensorCapture white = simulateCapture(*builtinScene("white", camera), camera, {.samplesPerPixel = 9});
    const auto [columns, rows] = camera.microlensCounts();
    // Centroids of pixel-integrated discs are off by up to ~0.2 px depending on where the disc
    // falls on the pixel grid; that error varies from lens to lens, while a wrong lattice (pitch,
    // rotation, offset, hexagonal row shift) shows up as a mean offset or a trend with position.
    int measured = 0;
    double worst = 0, meanX = 0, meanY = 0, trend[4] = {0, 0, 0, 0}, norm = 0;
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < columns; ++i) {
        const auto centre = camera.microlensImageCentrePx(i, j);
        if (centre[0] < 6 || centre[1] < 6 || centre[0] > 144 || centre[1] > 144) continue;  // fully on the sensor
        const Spot spot = measureSpot(white.irradiance, centre[0], centre[1], 5.5);
        const double ex = spot.x - centre[0], ey = spot.y - centre[1];
        const double dx = centre[0] - 75, dy = centre[1] - 75;
        worst = std::max(worst, std::hypot(ex, ey));
        meanX += ex;
        meanY += ey;
        trend[0] += ex * dx;
        trend[1] += ex * dy;
        trend[2] += ey * dx;
        trend[3] += ey * dy;
        norm += 0.5 * (dx * dx + dy * dy);
        ++measured;
      }
    ASSERT_GT(measured, 40);
    EXPECT_LT(worst, 0.25);
    EXPECT_LT(std::hypot(meanX, meanY) / measured, 0.03);
    for (double t : trend) EXPECT_LT(std::abs(t / norm), 1e-3);  // pitch and rotation
  }
}

// Every sample of a hexagonal microlens lands inside its cell: the flat tops of a white image are
// as smooth as a square array's even at 4 samples per pixel (rejecting samples of the bounding
// box made each pixel as noisy as the count that landed inside: about 20%).
TEST(SimulateLattice, HexagonalWhiteImagesHaveFlatTops) {
  for (Packing packing : {Packing::Square, Packing::Hexagonal}) {
    SCOPED_TRACE(packingName(packing));
    CameraModel camera = latticeCamera(packing);
    camera.mainLens.setImageSideFNumber(camera.microlenses->fNumber());  // images that touch
    const SensorCapture white = simulateCapture(*builtinScene("white", camera), camera, {.samplesPerPixel = 4});
    const auto [columns, rows] = camera.microlensCounts();
    double sum = 0, squares = 0;
    int count = 0;
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < columns; ++i) {
        const auto centre = camera.microlensImageCentrePx(i, j);
        for (int y = int(centre[1]) - 3; y <= int(centre[1]) + 3; ++y)
          for (int x = int(centre[0]) - 3; x <= int(centre[0]) + 3; ++x) {
            if (x < 0 || y < 0 || x >= 150 || y >= 150 || std::hypot(x + 0.5 - centre[0], y + 0.5 - centre[1]) > 3)
              continue;
            const double v = white.irradiance.at(x, y, 0);
            sum += v;
            squares += v * v;
            ++count;
          }
      }
    ASSERT_GT(count, 1000);
    const double mean = sum / count, spread = std::sqrt(std::max(0.0, squares / count - mean * mean)) / mean;
    std::printf("[flat tops] %s: relative spread %.4f\n", packingName(packing), spread);
    EXPECT_LT(spread, 0.02);
  }
}

TEST(SimulateLattice, PinholeMainLensMakesSharpSpotsOnlyAtTheFocalLength) {
  // A main lens stopped down to image-side f/50 images its tiny aperture under each microlens
  // (section 5.1): a spot ~1 px wide when the sensor is one microlens focal length away, blurred
  // by the whole microlens aperture when it is not (section 3.1).
  auto spotRms = [](double separationFactor) {
    CameraModel camera = latticeCamera(Packing::Square);
    camera.microlenses->rotationDeg = 0;
    camera.microlenses->offsetMm = {0, 0};
    camera.mainLens.setImageSideFNumber(50);
    camera.microlenses->toSensorMm = separationFactor * camera.microlenses->focalLengthMm;
    camera.microlenses->columns = camera.microlenses->rows = 5;
    const SensorCapture white = simulateCapture(*builtinScene("white", camera), camera, {.samplesPerPixel = 16});
    const auto centre = camera.microlensImageCentrePx(2, 2);
    return measureSpot(white.irradiance, centre[0], centre[1], 6.5).rms;
  };
  const double focused = spotRms(1.0), misfocused = spotRms(1.3);
  std::printf("pinhole spot RMS radius: %.2f px at the microlens focal length, %.2f px at 1.3x\n", focused, misfocused);
  EXPECT_LT(focused, 0.8);
  // Geometry: the microlens aperture (14 px square) scaled by |1 - 1.3 + 1.3 b / F| ~ 0.3: RMS
  // radius 14 * 0.3 / sqrt(6) ~ 1.7 px.
  EXPECT_GT(misfocused, 1.4);
}

}  // namespace
}  // namespace lfcam
