// The capture chain of the experiments: scene -> traced irradiance -> raw frame -> light field or
// conventional photograph; and the cameras and targets of section 6.
#include <algorithm>
#include <cmath>

#include "experiments/experiment_support.hpp"
#include "lfcam/decode/decode.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "simulate/simulated_grid.hpp"

namespace lfcam::experiments {

Scene whiteScene() {
  Scene scene;
  scene.name = "white";
  scene.background = {1, 1, 1};
  return scene;
}

Image forDisplay(const Image& photo, int scale, double peak) {
  if (!(peak > 0))
    for (float v : photo.pixels()) peak = std::max(peak, double(v));
  if (!(peak > 0)) peak = 1;
  Image out(photo.width() * scale, photo.height() * scale, 1);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) out.at(x, y, 0) = float(photo.at(x / scale, y / scale, 0) / peak);
  return out;
}

Result<TracedCapture> traceCapture(const Scene& scene, const CameraModel& camera, int samplesPerPixel, int traces) {
  LFCAM_TRY(camera.validate("experiment camera"));
  SimulationOptions options;
  options.samplesPerPixel = samplesPerPixel;
  TracedCapture traced{camera, simulateCapture(scene, camera, options).irradiance,
                       simulateCapture(whiteScene(), camera, options).irradiance};
  // More rays than one trace allows: traces with other sample positions (seeds), averaged.
  for (int k = 1; k < traces; ++k) {
    CameraModel reseeded = camera;
    reseeded.sensor.seed = camera.sensor.seed + std::uint64_t(k);
    const Image more = simulateCapture(scene, reseeded, options).irradiance;
    auto sum = traced.irradiance.pixels();
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += more.pixels()[i];
  }
  for (float& e : traced.irradiance.pixels()) e /= float(std::max(1, traces));
  return traced;
}

namespace {

// Raw frame in scene radiance units per pixel: (DN - black) / gain is electrons; a white field
// gives exposure * electronsPerIrradiance * whiteIrradiance of them.
Image radianceFrame(const TracedCapture& traced, bool noise, std::uint64_t seed) {
  Sensor sensor = traced.camera.sensor;
  sensor.noise = noise;
  sensor.seed = seed;
  sensor.colorFilter = ColorFilter::Mono;
  const Image raw = applySensor(traced.irradiance, sensor);
  Image radiance(raw.width(), raw.height(), 1);
  const double perUnit = sensor.gain() * sensor.exposure * sensor.electronsPerIrradiance;
  const auto in = raw.pixels();
  const auto white = traced.whiteIrradiance.pixels();
  auto out = radiance.pixels();
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = white[i] > 0 ? float((double(in[i]) - sensor.blackLevel) / (perUnit * white[i])) : 0.0f;
  return radiance;
}

}  // namespace

// The paper's chain: the raw frame (sensor model with its own seed) decoded by decodeLightField
// on the simulator's true grid, devignetted by the white image: the noise-free response to a
// white field, in the raw's normalised units ((DN - black) / (white level - black)), so that
// decoded values are scene radiance.
Result<LightField> captureLightField(const TracedCapture& traced, bool noise, std::uint64_t seed) {
  const CameraModel& camera = traced.camera;
  if (!camera.microlenses) return makeError(ErrorCode::Usage, "light-field capture: the camera has no microlens array");
  Sensor sensor = camera.sensor;
  sensor.noise = noise;
  sensor.seed = seed;
  sensor.colorFilter = ColorFilter::Mono;
  RawImage raw;
  raw.mosaic = applySensor(traced.irradiance, sensor);
  raw.colorFilter = ColorFilter::Mono;
  raw.blackLevel = sensor.blackLevel;
  raw.whiteLevel = sensor.whiteLevel;
  raw.source = "simulator";
  const double perUnit =
      sensor.gain() * sensor.exposure * sensor.electronsPerIrradiance / (sensor.whiteLevel - sensor.blackLevel);
  Image white(traced.whiteIrradiance.width(), traced.whiteIrradiance.height(), 1);
  const auto in = traced.whiteIrradiance.pixels();
  auto out = white.pixels();
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = float(in[i] * perUnit);
  DecodeOptions options;
  options.whiteImage = &white;
  options.repairHotPixels = false;  // the experiments' sensors have none; shot noise must stay
  options.views = int(std::lround(camera.microlenses->pitchMm *
                                  (1 + camera.microlenses->separationMm() / camera.mainLens.imageDistanceMm()) /
                                  camera.sensor.pixelPitchMm));
  Optics optics;
  optics.lensStepMm =
      camera.mainLens.imageDistanceMm() * camera.sensor.pixelPitchMm / camera.microlenses->separationMm();
  optics.spatialStepMm = camera.microlenses->pitchMm;
  optics.lensToMicrolensMm = camera.mainLens.imageDistanceMm();
  optics.focalLengthMm = camera.mainLens.focalLengthMm;
  options.optics = optics;
  LFCAM_ASSIGN_OR_RETURN(auto lf, decodeLightField(raw, gridFromCamera(camera), options));
  lf.metadata.source = "lfcam experiment: simulated raw frame, decoded";
  return lf;
}

Result<Image> conventionalPhoto(const TracedCapture& traced, bool noise, std::uint64_t seed) {
  if (traced.camera.microlenses) return makeError(ErrorCode::Usage, "conventional photo: the camera has microlenses");
  return radianceFrame(traced, noise, seed);  // upright: the raw is stored as a camera reads it out
}

CameraModel plenopticCamera(int microlenses, int pixelsPerMicrolens, double focusMm) {
  CameraModel camera = CameraModel::paperPrototype();
  camera.mainLens.focusDistanceMm = focusMm;
  camera.mainLens.setImageSideFNumber(camera.microlenses->fNumber());
  MicrolensArray& m = *camera.microlenses;
  m.columns = m.rows = microlenses;
  // The microlens images are spaced pitch (F + separation) / F on the sensor: N whole pixels.
  const double F = camera.mainLens.imageDistanceMm();
  camera.sensor.pixelPitchMm = m.pitchMm * (F + m.separationMm()) / F / pixelsPerMicrolens;
  camera.sensor.width = camera.sensor.height = microlenses * pixelsPerMicrolens;
  camera.sensor.colorFilter = ColorFilter::Mono;
  return camera;
}

CameraModel conventionalCamera(const CameraModel& plenoptic, double fNumber) {
  CameraModel camera = plenoptic;
  const auto counts = plenoptic.microlensCounts();
  const double pitch = plenoptic.microlenses->pitchMm;
  const double area = (pitch / plenoptic.sensor.pixelPitchMm) * (pitch / plenoptic.sensor.pixelPitchMm);
  camera.microlenses.reset();
  camera.mainLens.setImageSideFNumber(fNumber);
  camera.sensor.pixelPitchMm = pitch;
  camera.sensor.width = counts[0];
  camera.sensor.height = counts[1];
  camera.sensor.electronsPerIrradiance *= area;
  camera.sensor.fullWellElectrons *= area;
  camera.sensor.readNoiseElectrons *= std::sqrt(area);  // the read noise of area pixels, added
  // 16 bits, so that the quantisation step stays small against the shot noise of the big well.
  camera.sensor.bitDepth = 16;
  camera.sensor.whiteLevel = 65535;
  return camera;
}

double defocusedDistanceMm(const CameraModel& plenoptic, double blurMicrolenses) {
  const MainLens& lens = plenoptic.mainLens;
  const double F = lens.imageDistanceMm();
  const double aperture = F / plenoptic.microlenses->fNumber();  // image-side f/4
  // Blur b = aperture (F' - F) / F' on the microlens plane for an image at F' > F.
  const double imageDistance = F / (1 - blurMicrolenses * plenoptic.microlenses->pitchMm / aperture);
  return 1 / (1 / lens.focalLengthMm - 1 / imageDistance);
}

Scene pinholeScene(const CameraModel& plenoptic, double distanceMm) {
  Scene scene;
  scene.name = "pinhole";
  PointLight light;
  light.name = "pinhole";
  light.positionMm = {0, 0, distanceMm};
  const double F = plenoptic.mainLens.imageDistanceMm();
  light.radiusMm = 0.5 * plenoptic.microlenses->pitchMm * distanceMm / F;
  scene.lights.push_back(light);
  scene.camera = plenoptic;
  return scene;
}

Scene chartScene(const CameraModel& plenoptic, double distanceMm) {
  Scene scene;
  scene.name = "chart";
  const double F = plenoptic.mainLens.imageDistanceMm();
  const auto counts = plenoptic.microlensCounts();
  const double patch = plenoptic.microlenses->pitchMm * distanceMm / F;  // target mm per microlens
  Plane chart;
  chart.name = "chart";
  chart.centreMm = {0, 0, distanceMm};
  chart.widthMm = chart.heightMm = 1.2 * counts[0] * patch;
  chart.texture.kind = TextureKind::Chart;
  chart.texture.dark = {0.05f, 0.05f, 0.05f};
  chart.texture.light = {0.9f, 0.9f, 0.9f};
  chart.texture.groups = 5;
  chart.texture.minFrequency = 0.04 / patch;  // cycles per microlens on the target
  chart.texture.maxFrequency = 0.4 / patch;
  scene.planes.push_back(chart);
  scene.background = {0.2f, 0.2f, 0.2f};
  scene.camera = plenoptic;
  return scene;
}

}  // namespace lfcam::experiments
