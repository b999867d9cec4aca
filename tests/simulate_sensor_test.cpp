// The simulated sensor: determinism per seed, noise variance as modelled, colour filter, hot
// pixels; and the outputs of writeSimulation (ground truth, camera.json).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/parallel.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "simulate/simulated_grid.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

CameraModel tinyCamera(int pixels) {
  CameraModel camera = CameraModel::paperPrototype(pixels, pixels);
  camera.microlenses->pitchMm = 14 * 0.009;
  camera.microlenses->focalLengthMm = 4 * camera.microlenses->pitchMm;
  return camera;
}

bool sameImage(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin());
}

TEST(SimulateSensor, SameSeedSameImageWhateverTheThreads) {
  const CameraModel camera = tinyCamera(84);
  const Scene scene = *builtinScene("people", camera);
  const SensorCapture a = simulateCapture(scene, camera, {.samplesPerPixel = 4});
  setThreadCount(1);
  const SensorCapture b = simulateCapture(scene, camera, {.samplesPerPixel = 4});
  setThreadCount(0);
  EXPECT_TRUE(sameImage(a.raw, b.raw));
  EXPECT_TRUE(sameImage(a.irradiance, b.irradiance));
  CameraModel other = camera;
  other.sensor.seed = 2;
  const SensorCapture c = simulateCapture(scene, other, {.samplesPerPixel = 4});
  EXPECT_FALSE(sameImage(a.raw, c.raw));
}

TEST(SimulateSensor, NoiseVarianceMatchesTheModel) {
  // A uniform irradiance through the sensor model with two seeds: the difference has twice the
  // variance of one capture, gain^2 (mean electrons + read noise^2) + 1/12 (quantisation), in DN^2.
  Sensor sensor;
  sensor.readNoiseElectrons = 20;
  Image irradiance(128, 128, 1);
  const double irradianceLevel = 0.02;  // 4000 electrons
  for (float& v : irradiance.pixels()) v = float(irradianceLevel);
  const Image a = applySensor(irradiance, sensor);
  sensor.seed = 2;
  const Image b = applySensor(irradiance, sensor);
  EXPECT_FALSE(sameImage(a, b));
  double sum = 0, sum2 = 0, mean = 0;
  const std::size_t n = a.pixels().size();
  for (std::size_t k = 0; k < n; ++k) {
    const double d = double(a.pixels()[k]) - b.pixels()[k];
    sum += d;
    sum2 += d * d;
    mean += a.pixels()[k];
  }
  mean /= n;
  const double variance = (sum2 - sum * sum / n) / (n - 1) / 2;
  const double electrons = irradianceLevel * sensor.exposure * sensor.electronsPerIrradiance;
  const double expected =
      sensor.gain() * sensor.gain() * (electrons + sensor.readNoiseElectrons * sensor.readNoiseElectrons) + 1.0 / 12;
  std::printf("noise: variance %.3f DN^2 measured, %.3f predicted; mean %.2f DN, predicted %.2f\n", variance, expected,
              mean, sensor.blackLevel + electrons * sensor.gain());
  EXPECT_NEAR(variance / expected, 1.0, 0.05);
  EXPECT_NEAR(mean, sensor.blackLevel + electrons * sensor.gain(), 0.5);
  // Without noise: exactly the rounded mean.
  sensor.noise = false;
  const Image c = applySensor(irradiance, sensor);
  EXPECT_EQ(c.at(5, 7, 0), float(std::round(sensor.blackLevel + electrons * sensor.gain())));
}

TEST(SimulateSensor, DimPixelsArePoisson) {
  // One DN per electron and no read noise: the codes minus black are the photo-electrons, whose
  // mean and variance are both the expected count (here 5: the small-mean branch).
  Sensor sensor;
  sensor.readNoiseElectrons = 0;
  sensor.fullWellElectrons = sensor.whiteLevel - sensor.blackLevel;
  Image irradiance(128, 128, 1);
  for (float& v : irradiance.pixels()) v = float(5.0 / sensor.electronsPerIrradiance);
  const Image raw = applySensor(irradiance, sensor);
  double sum = 0, sum2 = 0;
  for (float v : raw.pixels()) {
    sum += v - sensor.blackLevel;
    sum2 += double(v - sensor.blackLevel) * (v - sensor.blackLevel);
  }
  const double n = double(raw.pixels().size()), mean = sum / n, variance = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 5.0, 0.1);
  EXPECT_NEAR(variance, 5.0, 0.25);
}

TEST(SimulateSensor, HotPixelsAndClipping) {
  Sensor sensor;
  sensor.hotPixelFraction = 0.01;
  sensor.noise = false;
  Image irradiance(100, 100, 1);
  irradiance.at(3, 3, 0) = 10.0f;  // far beyond the full well
  const Image raw = applySensor(irradiance, sensor);
  int hot = 0;
  for (float v : raw.pixels()) hot += v == float(sensor.whiteLevel);
  EXPECT_GT(hot, 50);
  EXPECT_LT(hot, 170);
  EXPECT_EQ(raw.at(3, 3, 0), float(sensor.whiteLevel));
}

TEST(SimulateSensor, ColorFilterPatterns) {
  EXPECT_EQ(colorFilterChannel(ColorFilter::RGGB, 0, 0), 0);
  EXPECT_EQ(colorFilterChannel(ColorFilter::RGGB, 1, 1), 2);
  EXPECT_EQ(colorFilterChannel(ColorFilter::BGGR, 0, 0), 2);
  EXPECT_EQ(colorFilterChannel(ColorFilter::GRBG, 1, 0), 0);
  EXPECT_EQ(colorFilterChannel(ColorFilter::GBRG, 0, 1), 0);
  EXPECT_EQ(colorFilterChannel(ColorFilter::Mono, 0, 0), -1);
  // A red scene lights only the red pixels of an RGGB mosaic.
  CameraModel camera = tinyCamera(28);
  camera.sensor.noise = false;
  Scene scene;
  scene.background = {1, 0, 0};
  const SensorCapture capture = simulateCapture(scene, camera, {.samplesPerPixel = 1});
  EXPECT_GT(capture.irradiance.at(14, 14, 0), 0);  // under the one microlens
  EXPECT_EQ(capture.irradiance.at(15, 14, 0), 0);
  EXPECT_EQ(capture.irradiance.at(15, 15, 0), 0);
}

TEST(SimulateOutputs, GroundTruthAndCameraFile) {
  test::TempDir dir;
  CameraModel camera = tinyCamera(84);
  Scene scene;
  scene.name = "card";
  Plane plane;
  plane.centreMm = {0, 0, 500};
  plane.widthMm = plane.heightMm = 100;
  plane.texture.kind = TextureKind::Checkerboard;
  plane.texture.periodMm = 3;
  scene.planes.push_back(plane);
  ASSERT_TRUE(writeSimulation(dir / "out", scene, camera, {.samplesPerPixel = 1}));
  for (const char* name : {"raw.png", "white.png", "camera.json", "depth.pfm", "ideal.lf.h5"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / name)) << name;

  auto raw = readImage(dir / "out" / "raw.png");
  ASSERT_TRUE(raw);
  EXPECT_EQ(raw->width(), 84);
  auto depth = readImage(dir / "out" / "depth.pfm");
  ASSERT_TRUE(depth);
  const auto [columns, rows] = camera.microlensCounts();
  EXPECT_EQ(depth->width(), columns);
  EXPECT_NEAR(depth->at(columns / 2, rows / 2, 0), 500.0, 1e-3);

  auto lf = readLightField(dir / "out" / "ideal.lf.h5");
  ASSERT_TRUE(lf);
  EXPECT_EQ(lf->ns(), columns);
  EXPECT_EQ(lf->nu(), 14);
  ASSERT_TRUE(lf->metadata.optics);
  EXPECT_NEAR(lf->metadata.optics->lensToMicrolensMm, camera.mainLens.imageDistanceMm(), 1e-9);
  EXPECT_TRUE(lf->hasWeight());

  std::ifstream in(dir / "out" / "camera.json");
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_EQ(json["lattice_px"]["packing"], "square");
  EXPECT_NEAR(json["lattice_px"]["pitch_px"].get<double>(), 14 * (1 + 0.504 / camera.mainLens.imageDistanceMm()), 1e-9);
  EXPECT_EQ(json["microlenses"]["columns"], columns);
}

TEST(SimulateOutputs, RawOverWhiteIsTheIdealLightField) {
  // A card in the focal plane: each microlens image is uniform (Figure 13), and the raw divided
  // by the white image at the image's centre is the radiance of the ideal light field at that
  // microlens: (s, t) is microlens (i, j) = (s, t) of the raw's grid, which is stored upright.
  CameraModel camera = tinyCamera(168);
  camera.sensor.noise = false;
  camera.sensor.colorFilter = ColorFilter::Mono;
  Scene scene;
  Plane plane;
  const double period =
      3 * 0.126 * camera.mainLens.focusDistanceMm / camera.mainLens.imageDistanceMm();  // 3 microlenses
  // Off centre by a third of a square, so that turning the pattern 180 degrees changes it.
  plane.centreMm = {period / 3, 0, camera.mainLens.focusDistanceMm};
  plane.widthMm = plane.heightMm = 100;
  plane.texture.kind = TextureKind::Checkerboard;
  plane.texture.periodMm = period;
  plane.texture.dark = {0.2f, 0.2f, 0.2f};
  plane.texture.light = {0.8f, 0.8f, 0.8f};
  scene.planes.push_back(plane);
  const SensorCapture raw = simulateCapture(scene, camera, {.samplesPerPixel = 4});
  const SensorCapture white = simulateCapture(*builtinScene("white", camera), camera, {.samplesPerPixel = 4});
  auto lf = idealLightField(scene, camera);
  ASSERT_TRUE(lf);
  const LensletGrid grid = gridFromCamera(camera);
  const int u = lf->nu() / 2, v = lf->nv() / 2;
  int compared = 0;
  for (int t = 1; t + 1 < grid.rows; ++t)
    for (int s = 1; s + 1 < grid.columns; ++s) {
      bool uniform = true;  // away from the checkerboard's edges
      for (int dt = -1; dt <= 1; ++dt)
        for (int ds = -1; ds <= 1; ++ds) uniform &= lf->at(u, v, s + ds, t + dt, 0) == lf->at(u, v, s, t, 0);
      if (!uniform) continue;
      const auto centre = grid.centre(s, t);
      const int x = int(centre[0]), y = int(centre[1]);
      EXPECT_NEAR(raw.irradiance.at(x, y, 0) / white.irradiance.at(x, y, 0), lf->at(u, v, s, t, 0), 0.01)
          << "microlens " << s << ", " << t;
      ++compared;
    }
  EXPECT_GT(compared, 8);
}

TEST(SimulateOutputs, IdealLightFieldDisparityHasThePaperSign) {
  // A card nearer than the focus plane has positive slope: it appears in view u displaced by
  // -u * slope (light_field.hpp), with slope = (du / ds) (1 - 1 / alpha).
  CameraModel camera = tinyCamera(280);
  Scene scene;
  Plane plane;
  plane.centreMm = {0, 0, 440};  // focus at 457.2 mm: slope ~0.5 px per view
  plane.widthMm = plane.heightMm = 200;
  plane.texture.kind = TextureKind::Edge;
  plane.texture.dark = {0, 0, 0};
  plane.texture.light = {1, 1, 1};
  scene.planes.push_back(plane);
  auto lf = idealLightField(scene, camera);
  ASSERT_TRUE(lf);
  // Position of the edge (first light sample) along s in the middle row of a view.
  auto edge = [&](int u) {
    const int t = lf->nt() / 2, v = lf->nv() / 2;
    double sum = 0;
    for (int s = 0; s < lf->ns(); ++s) sum += lf->at(u, v, s, t, 0);
    return lf->ns() - sum;  // dark samples = where the edge is (light on the right, upright)
  };
  const double left = edge(2), right = edge(lf->nu() - 3);
  EXPECT_GT(left, right);  // views to the right see the near edge further left: -u * slope, slope > 0
}

}  // namespace
}  // namespace lfcam
