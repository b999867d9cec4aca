// A small simulated focused plenoptic camera and scenes placed at chosen virtual depths, for the
// tests of src/focused (their ground truth comes from the simulator: simulate/focused_truth.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "lfcam/focused/seam_energy.hpp"
#include "lfcam/simulate/camera_model.hpp"
#include "lfcam/simulate/focused_truth.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"

namespace lfcam::test {

struct FocusedCameraSpec {
  int width = 640, height = 480;
  double micro = 20;       // micro-image pitch, pixels
  bool galilean = true;    // Raytrix's (upright micro-images); else Keplerian (inverted)
  bool multiFocus = true;  // three lens types, else one
  Packing packing = Packing::Hexagonal;
};

// 5.5 um pixels, a 50 mm main lens, microlenses 0.4 mm from the sensor; Galilean: the microlenses'
// plane conjugate to 2 m, the three types sharp near v = 3, 4.5 and 7; Keplerian: conjugate to
// 0.6 m, one type sharp near v = 3 (or three near 2.5, 4 and 6). The main lens's image-side
// f-number matches the microlenses' pitch, so micro-images nearly touch.
inline CameraModel focusedCamera(const FocusedCameraSpec& spec = {}) {
  CameraModel camera;
  camera.sensor.width = spec.width;
  camera.sensor.height = spec.height;
  camera.sensor.pixelPitchMm = 0.0055;
  camera.sensor.colorFilter = ColorFilter::Mono;
  camera.sensor.noise = false;
  camera.mainLens.focalLengthMm = 50;
  camera.mainLens.focusDistanceMm = spec.galilean ? 2000 : 600;
  MicrolensArray m;
  m.packing = spec.packing;
  m.toSensorMm = 0.4;
  const double b = 0.4, F = camera.mainLens.imageDistanceMm();
  m.pitchMm = spec.micro * camera.sensor.pixelPitchMm / (1 + b / F);
  // A lens sharp at virtual depth v (nearly a / b): Galilean f = b v / (v - 1), Keplerian b v / (v + 1).
  auto focal = [&](double v) { return spec.galilean ? b * v / (v - 1) : b * v / (v + 1); };
  if (spec.multiFocus)
    m.typeFocalLengthsMm = spec.galilean ? std::vector<double>{focal(3), focal(4.5), focal(7)}
                                         : std::vector<double>{focal(2.5), focal(4), focal(6)};
  m.focalLengthMm = spec.multiFocus ? m.typeFocalLengthsMm[0] : focal(3);
  camera.microlenses = m;
  camera.mainLens.setImageSideFNumber(1.04 * b / m.pitchMm);
  return camera;
}

// A fronto-parallel plane at virtual depth v filling the field of view (times `extent`), with a
// grey value-noise texture whose features are `featurePx` photograph pixels at pixelsPerLens.
inline Plane focusedPlane(const CameraModel& camera, const std::string& name, double v, double extent, double featurePx,
                          double pixelsPerLens, std::uint64_t seed) {
  const double z = depthOfFocusedVirtualDepth(camera, v);
  const double F = camera.mainLens.imageDistanceMm(), b = camera.microlenses->separationMm();
  // Image pixels -> the microlenses' plane -> the object at z through the main lens's centre.
  const double objectPerImagePx = camera.sensor.pixelPitchMm * F / (F + b) * z / F;
  Plane plane;
  plane.name = name;
  plane.centreMm = {0, 0, z};
  plane.widthMm = extent * camera.sensor.width * objectPerImagePx;
  plane.heightMm = extent * camera.sensor.height * objectPerImagePx;
  plane.texture.kind = TextureKind::Noise;
  plane.texture.dark = {0.1f, 0.1f, 0.1f};
  plane.texture.light = {0.9f, 0.9f, 0.9f};
  const double micro = camera.microlenses->pitchMm * (1 + b / F) / camera.sensor.pixelPitchMm;  // D
  plane.texture.periodMm = featurePx * objectPerImagePx * micro / pixelsPerLens;
  plane.texture.seed = seed;
  return plane;
}

// `plane` alone before a mid-grey background.
inline Scene oneSurface(const CameraModel& camera, const std::string& name, const Plane& plane) {
  Scene scene;
  scene.name = name;
  scene.camera = camera;
  scene.background = {0.5f, 0.5f, 0.5f};
  scene.planes.push_back(plane);
  return scene;
}

// Three planes: the background at v_far, and two cards nearer the camera (larger v on a Galilean
// camera, smaller on a Keplerian one) over parts of it.
inline Scene focusedLayers(const CameraModel& camera, const std::array<double, 3>& virtualDepths,
                           double pixelsPerLens) {
  Scene scene;
  scene.name = "focused layers";
  scene.camera = camera;
  scene.background = {0.5f, 0.5f, 0.5f};
  scene.planes.push_back(focusedPlane(camera, "background", virtualDepths[0], 1.6, 4, pixelsPerLens, 1));
  Plane left = focusedPlane(camera, "left card", virtualDepths[1], 0.45, 3, pixelsPerLens, 2);
  left.centreMm[0] = -0.3 * left.widthMm / 0.45;
  Plane right = focusedPlane(camera, "right card", virtualDepths[2], 0.4, 3, pixelsPerLens, 3);
  right.centreMm[0] = 0.3 * right.widthMm / 0.4;
  right.centreMm[1] = 0.15 * right.heightMm / 0.4;
  scene.planes.push_back(left);
  scene.planes.push_back(right);
  return scene;
}

inline constexpr double kFocusedPixelsPerLens = 5;

// One simulated capture (noise free, devignetted by its white image) with its truth on the frame of
// `pixelsPerLens`.
struct FocusedCapture {
  CameraModel camera;
  FocusedCalibration calibration;
  Image image;       // radiance: the capture over the white image
  Image raw, white;  // the sensor's irradiance, vignetted, and the white image's
  FocusedTruth truth;
};

// `scene` through `camera`, devignetted by the white image, with its truth on the frame of
// pixelsPerLens. electronsAtWhite > 0: photon noise, the white's brightest pixel collecting that
// many electrons (0: noise free).
inline FocusedCapture simulateFocusedScene(const CameraModel& camera, const Scene& scene, double pixelsPerLens,
                                           int samplesPerPixel = 16, double electronsAtWhite = 0) {
  FocusedCapture c;
  c.camera = camera;
  const SensorCapture capture = simulateCapture(scene, c.camera, {.samplesPerPixel = samplesPerPixel});
  const SensorCapture white =
      simulateCapture(builtinScene("white", c.camera).value(), c.camera, {.samplesPerPixel = samplesPerPixel});
  float brightest = 0;
  for (const float x : white.irradiance.pixels()) brightest = std::max(brightest, x);
  const int width = camera.sensor.width, height = camera.sensor.height;
  c.image = Image(width, height, 1);
  c.raw = Image(width, height, 1);
  c.white = Image(width, height, 1);
  std::copy(capture.irradiance.pixels().begin(), capture.irradiance.pixels().end(), c.raw.pixels().begin());
  std::copy(white.irradiance.pixels().begin(), white.irradiance.pixels().end(), c.white.pixels().begin());
  if (electronsAtWhite > 0) {
    std::mt19937_64 random(7);
    const double gain = electronsAtWhite / brightest;
    for (float& x : c.raw.pixels()) x = float(std::poisson_distribution<long>(std::max(0.0, x * gain))(random) / gain);
  }
  for (std::size_t k = 0; k < c.image.pixels().size(); ++k) {
    const float w = white.irradiance.pixels()[k];
    c.image.pixels()[k] = w > 0.05f * brightest ? c.raw.pixels()[k] / w : 0.0f;
  }
  c.calibration = focusedCalibrationFromCamera(c.camera).value();
  c.truth = focusedTruth(scene, c.camera, focusedPhotoFrame(c.calibration, pixelsPerLens)).value();
  return c;
}

inline FocusedCapture simulateFocused(const test::FocusedCameraSpec& spec, const std::array<double, 3>& virtualDepths,
                                      double pixelsPerLens = kFocusedPixelsPerLens, int samplesPerPixel = 16) {
  const CameraModel camera = focusedCamera(spec);
  return simulateFocusedScene(camera, focusedLayers(camera, virtualDepths, pixelsPerLens), pixelsPerLens,
                              samplesPerPixel);
}

struct CentreErrors {
  double worst = 0, rms = 0;
};

// Over the true micro-image centres inside the image, `margin` pixels or more from its sides: the
// distance to the nearest found one.
inline CentreErrors centreErrors(const FocusedCalibration& found, const FocusedCalibration& truth, double margin = 0) {
  CentreErrors errors;
  int count = 0;
  for (int j = 0; j < truth.grid.rows; ++j)
    for (int i = 0; i < truth.grid.columns; ++i) {
      const auto t = truth.grid.centre(i, j);
      if (t[0] < margin || t[1] < margin || t[0] > truth.imageWidth - margin || t[1] > truth.imageHeight - margin)
        continue;
      double nearest = 1e9;
      for (int fj = 0; fj < found.grid.rows; ++fj)
        for (int fi = 0; fi < found.grid.columns; ++fi) {
          const auto f = found.grid.centre(fi, fj);
          nearest = std::min(nearest, std::hypot(f[0] - t[0], f[1] - t[1]));
        }
      errors.worst = std::max(errors.worst, nearest);
      errors.rms += nearest * nearest;
      ++count;
    }
  errors.rms = std::sqrt(errors.rms / std::max(count, 1));
  return errors;
}

// A virtual depth map against the truth, leaving out `margin` pixels at each side.
struct VirtualDepthScore {
  double badPix = 0;         // share of pixels whose disparity D / v is off by more than 0.25 px
  double relativeError = 0;  // mean |v - v_true| / v_true
};

inline VirtualDepthScore scoreVirtualDepth(const Image& estimate, const Image& truth, double diameter, int margin) {
  VirtualDepthScore s;
  int count = 0;
  for (int y = margin; y < truth.height() - margin; ++y)
    for (int x = margin; x < truth.width() - margin; ++x) {
      const double v = estimate.at(x, y, 0), t = truth.at(x, y, 0);
      s.badPix += std::abs(diameter / v - diameter / t) > 0.25;
      s.relativeError += std::abs(v - t) / t;
      ++count;
    }
  s.badPix /= count;
  s.relativeError /= count;
  return s;
}

// PSNR (peak 1) of channel 0 of `a` against `b`'s, leaving out `margin` pixels at each side.
inline double psnr(const Image& a, const Image& b, int margin) {
  double sum = 0;
  int count = 0;
  for (int y = margin; y < a.height() - margin; ++y)
    for (int x = margin; x < a.width() - margin; ++x) {
      const double d = a.at(x, y, 0) - b.at(x, y, 0);
      sum += d * d;
      ++count;
    }
  return 10 * std::log10(count / sum);
}

// Seams as errors: the seam energy (seam_energy.hpp) of `photo` less the ideal photograph, over the
// ideal's own. Seam energy over the ideal's is 1 for the ideal itself and grows with sharpness, so
// it cannot tell a sharp rendering from seams; the error's is 0 for the ideal, high for patches.
inline double seamError(const Image& photo, const Image& ideal, const FocusedCalibration& calibration,
                        double pixelsPerLens) {
  Image error = photo.copy();
  for (int c = 0; c < error.channels(); ++c)
    for (std::size_t k = 0; k < error.pixels().size() / std::size_t(error.channels()); ++k)
      error.plane(c)[k] -= ideal.plane(std::min(c, ideal.channels() - 1))[k];
  return seamEnergy(error, calibration, pixelsPerLens) / seamEnergy(ideal, calibration, pixelsPerLens);
}

// The Galilean multi-focus camera looking at layers at virtual depths 3.2, 4.6 and 6, simulated once.
inline const FocusedCapture& galileanCapture() {
  static const auto capture = std::make_unique<FocusedCapture>(simulateFocused({}, {3.2, 4.6, 6.0}));
  return *capture;
}

}  // namespace lfcam::test
