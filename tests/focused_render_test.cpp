// Rendering a focused plenoptic capture, against the simulator's ideal photograph.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "focused_camera.hpp"
#include "lfcam/focused/focused_render.hpp"

namespace lfcam {
namespace {

constexpr double kPixelsPerLens = 5;

// One simulated capture (noise free, devignetted by its white image) with its truth.
struct FocusedCapture {
  CameraModel camera;
  FocusedCalibration calibration;
  Image image;  // radiance: the capture over the white image
  FocusedTruth truth;
};

FocusedCapture simulateFocused(const test::FocusedCameraSpec& spec, const std::array<double, 3>& virtualDepths) {
  FocusedCapture c;
  c.camera = test::focusedCamera(spec);
  const Scene scene = test::focusedLayers(c.camera, virtualDepths, kPixelsPerLens);
  const SensorCapture capture = simulateCapture(scene, c.camera, {.samplesPerPixel = 16});
  const SensorCapture white =
      simulateCapture(builtinScene("white", c.camera).value(), c.camera, {.samplesPerPixel = 16});
  float brightest = 0;
  for (const float x : white.irradiance.pixels()) brightest = std::max(brightest, x);
  c.image = Image(spec.width, spec.height, 1);
  for (std::size_t k = 0; k < c.image.pixels().size(); ++k) {
    const float w = white.irradiance.pixels()[k];
    c.image.pixels()[k] = w > 0.05f * brightest ? capture.irradiance.pixels()[k] / w : 0.0f;
  }
  c.calibration = focusedCalibrationFromCamera(c.camera).value();
  c.truth = focusedTruth(scene, c.camera, focusedPhotoFrame(c.calibration, kPixelsPerLens)).value();
  return c;
}

const FocusedCapture& galileanCapture() {
  static const auto capture = std::make_unique<FocusedCapture>(simulateFocused({}, {3.2, 4.6, 6.0}));
  return *capture;
}

// PSNR (peak 1) of channel 0 of `a` against `b`'s, leaving out `margin` pixels at each side.
double psnr(const Image& a, const Image& b, int margin) {
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

TEST(FocusedRender, TotalFocusWithTheTrueDepthsMatchesTheIdealPhotograph) {
  const FocusedCapture& c = galileanCapture();
  FocusedRenderRequest request;
  request.pixelsPerLens = kPixelsPerLens;
  request.virtualDepthMap = &c.truth.virtualDepth;
  auto photo = renderFocused(c.image, c.calibration, request);
  ASSERT_TRUE(photo) << photo.error().message;
  const double db = psnr(*photo, c.truth.allInFocus, int(kPixelsPerLens));
  std::printf("total focus with the true virtual depths: PSNR %.2f dB\n", db);
  EXPECT_GT(db, 30);
}

}  // namespace
}  // namespace lfcam
