// Finding the views per lens of lenslet images that do not say: microscope-like frames (mostly
// dark, noisy, 16-bit), scenes textured at the lenses' scale, the simulator's and the layered
// planes' light fields; raw frames refused; unsure cases naming the plausible periods.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "core/power_spectrum.hpp"
#include "io/macro_pixel_period.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

using io::estimateMacroPixelPeriod;

TEST(PowerSpectrum, FastMatchesTheReference) {
  std::mt19937 random(3);
  std::normal_distribution<double> noise(5.0, 2.0);
  for (int n : {2, 3, 17, 64, 1463}) {
    std::vector<double> sequence(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) sequence[std::size_t(i)] = noise(random) + 3 * std::sin(0.3 * i);
    const auto fast = powerSpectrum(sequence), reference = powerSpectrumReference(sequence);
    ASSERT_EQ(fast.size(), std::size_t(n / 2 + 1));
    ASSERT_EQ(reference.size(), fast.size());
    const double peak = *std::max_element(reference.begin(), reference.end());
    for (std::size_t f = 0; f < fast.size(); ++f)
      EXPECT_NEAR(fast[f], reference[f], 1e-5 * peak + 1e-9) << n << " " << f;
  }
}

// Rounded to 16 bits, as a file would hold it.
float sixteenBit(double value) { return float(std::round(std::clamp(value, 0.0, 1.0) * 65535) / 65535); }

struct Frame {
  int views = 19;  // pixels per lens, across and down
  int lensesX = 77, lensesY = 67;
  double background = 0.01, noise = 0.01;
  double brightness = 0.3;                          // of the object under the lenses it covers
  int objectX = 30, objectY = 20, objectSize = 24;  // lenses
};

// A rectified light-field-microscope frame: each lens shows the disc of the objective's aperture
// (bright inside, falling off to its rim), lit only where an object (a ring, like a vesicle) lies;
// elsewhere dark background and noise.
Image microscopeFrame(const Frame& f, unsigned seed) {
  Image image(f.views * f.lensesX, f.views * f.lensesY, 1);
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, f.noise);
  const double centre = 0.5 * (f.views - 1), radius = 0.45 * f.views;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const int s = x / f.views, t = y / f.views;
      const double du = (x % f.views - centre) / radius, dv = (y % f.views - centre) / radius;
      const double aperture = std::clamp(1.2 * (1.0 - du * du - dv * dv), 0.0, 1.0);
      const double rx = (s - f.objectX - 0.5 * f.objectSize) / (0.5 * f.objectSize);
      const double ry = (t - f.objectY - 0.5 * f.objectSize) / (0.5 * f.objectSize);
      const double ring = std::exp(-std::pow((std::hypot(rx, ry) - 0.7) / 0.15, 2)) + 0.2 * (std::hypot(rx, ry) < 0.8);
      image.at(x, y, 0) = sixteenBit(f.background + f.brightness * ring * aperture + noise(random));
    }
  return image;
}

void expectPeriods(const Image& image, int across, int down, const std::string& what) {
  const auto x = estimateMacroPixelPeriod(image, true), y = estimateMacroPixelPeriod(image, false);
  EXPECT_EQ(x.period.value_or(0), across) << what;
  EXPECT_EQ(y.period.value_or(0), down) << what;
}

TEST(MacroPixelPeriod, MostlyDarkNoisyMicroscopeFrames) {
  // The reported frame's geometry: 19 pixels per lens, 77 x 67 lenses (1463 x 1273, where 7, 11,
  // 77, 133 and 209 also divide the width).
  const Image frame = microscopeFrame({}, 1);
  expectPeriods(frame, 19, 19, "19 px, 77 x 67 lenses");
  // Timed: the estimate runs on every read of such a file.
  double best = 1e9;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    const auto x = estimateMacroPixelPeriod(frame, true), y = estimateMacroPixelPeriod(frame, false);
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    ASSERT_TRUE(x.period && y.period);
  }
  std::printf("[ timing ] views per lens of a %dx%d 16-bit frame, both axes: %.1f ms\n", frame.width(), frame.height(),
              best);
  EXPECT_LT(best, 2000.0);

  // Other periods, sizes sharing factors with them, non-square, fainter and noisier.
  expectPeriods(microscopeFrame({.views = 15, .lensesX = 77, .lensesY = 67}, 2), 15, 15, "15 px in 1155 x 1005");
  expectPeriods(microscopeFrame({.views = 16, .lensesX = 64, .lensesY = 40, .objectX = 5, .objectY = 3}, 3), 16, 16,
                "16 px, 64 x 40 lenses");
  expectPeriods(microscopeFrame({.views = 12,
                                 .lensesX = 90,
                                 .lensesY = 48,
                                 .noise = 0.02,
                                 .brightness = 0.15,
                                 .objectX = 50,
                                 .objectY = 10,
                                 .objectSize = 16},
                                4),
                12, 12, "12 px, faint and noisy");
}

// A vignetted lenslet image of a scene that changes only from lens to lens: `brightness(s, t)`.
template <class Brightness>
Image texturedLenses(int views, int lensesX, int lensesY, Brightness brightness, double noiseLevel) {
  Image image(views * lensesX, views * lensesY, 1);
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, noiseLevel);
  const double centre = 0.5 * (views - 1);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const double du = (x % views - centre) / (0.5 * views), dv = (y % views - centre) / (0.5 * views);
      const double vignetting = std::max(0.0, 1.0 - 0.8 * (du * du + dv * dv));
      image.at(x, y, 0) = sixteenBit(vignetting * brightness(x / views, y / views) + noise(random));
    }
  return image;
}

TEST(MacroPixelPeriod, ScenesTexturedAtTwoLensesDoNotDoubleThePeriod) {
  // Twice the period divides the size too, and the image repeats exactly at it.
  for (int views : {9, 16}) {
    SCOPED_TRACE(views);
    expectPeriods(texturedLenses(
                      views, 40, 30, [](int s, int t) { return (s + t) % 2 ? 0.9 : 0.2; }, 0.01),
                  views, views, "checkerboard of lenses");
    expectPeriods(texturedLenses(
                      views, 40, 30, [](int s, int) { return s % 2 ? 0.9 : 0.2; }, 0.01),
                  views, views, "stripes one lens wide");
    expectPeriods(texturedLenses(
                      views, 40, 30, [](int, int t) { return t % 2 ? 0.9 : 0.2; }, 0.01),
                  views, views, "stripes one lens high");
    expectPeriods(
        texturedLenses(
            views, 48, 36,
            [](int s, int t) { return s < 10 || s >= 26 || t < 8 || t >= 20 ? 0.0
                                      : (s + t) % 2                         ? 0.5
                                                                            : 0.05; }, 0.02),
        views, views, "checkerboard in the dark");
  }
  // Without vignetting: lenses of flat brightness, told apart only by their borders.
  expectPeriods(texturedLenses(
                    9, 40, 30, [](int s, int t) { return (s + t) % 2 ? 0.9 : 0.2; }, 0.01),
                9, 9, "flat checkerboard");
}

// A light field written as a lenslet image without lfcam's description (as other tools write
// them), 16-bit.
std::filesystem::path writtenWithoutDescription(const LightField& lightField, const std::filesystem::path& path) {
  EXPECT_TRUE(writeLightField(path, lightField, {.sampleType = SampleType::UInt16}).ok());
  auto image = readImage(path);
  EXPECT_TRUE(image.ok());
  EXPECT_TRUE(writeImage(path, *image, {.sampleType = SampleType::UInt16}).ok());
  return path;
}

TEST(MacroPixelPeriod, LayeredPlanesAndSimulatedLightFieldsAsLensletImages) {
  test::TempDir dir;
  // Parallax only: every view is lit alike.
  const auto planes = renderLayeredPlanes(defaultLayeredPlanesScene(9, 160, 1, 120));
  const auto planesFile = writtenWithoutDescription(planes.lightField, dir / "planes.png");
  auto info = probeLightField(planesFile);
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info->shape, planes.lightField.shape());

  // The simulator's ideal light field of a camera like the paper's prototype, colour, 14 views.
  const CameraModel camera = CameraModel::paperPrototype(420, 280);
  auto scene = builtinScene("people", camera);
  ASSERT_TRUE(scene.ok());
  auto simulated = idealLightField(*scene, camera);
  ASSERT_TRUE(simulated.ok()) << simulated.error().message;
  const auto simulatedFile = writtenWithoutDescription(*simulated, dir / "simulated.tif");
  info = probeLightField(simulatedFile);
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info->shape, simulated->shape());
  auto read = readLightField(simulatedFile);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->shape(), simulated->shape());
}

TEST(MacroPixelPeriod, UnrectifiedRawFramesAreRefused) {
  // The raw frame of a microscope, before rectification: its lenses are 15.4 pixels apart, near
  // the 16 that divides both sides.
  // Each lens shows the aperture's disc.
  Image raw(400, 320, 1);
  const double pitch = 15.4;
  for (int y = 0; y < raw.height(); ++y)
    for (int x = 0; x < raw.width(); ++x) {
      const double du = (std::fmod(x + 0.5, pitch) - 0.5 * pitch) / (0.45 * pitch);
      const double dv = (std::fmod(y + 0.5, pitch) - 0.5 * pitch) / (0.45 * pitch);
      const double aperture = std::clamp(1.2 * (1.0 - du * du - dv * dv), 0.0, 1.0);
      raw.at(x, y, 0) = float(0.02 + aperture * (0.5 + 0.3 * std::sin(0.02 * x)));
    }
  EXPECT_FALSE(estimateMacroPixelPeriod(raw, true).period);
  EXPECT_FALSE(estimateMacroPixelPeriod(raw, false).period);
}

TEST(MacroPixelPeriod, UnsureEstimatesNameThePlausiblePeriods) {
  test::TempDir dir;
  // Ever fainter lenses under the same noise: found, then unsure (naming the period), then nothing.
  bool found = false, unsure = false;
  for (double brightness = 0.2; brightness > 0.002; brightness *= 0.8) {
    const Image frame = microscopeFrame({.views = 15,
                                         .lensesX = 40,
                                         .lensesY = 32,
                                         .noise = 0.02,
                                         .brightness = brightness,
                                         .objectX = 5,
                                         .objectY = 5,
                                         .objectSize = 20},
                                        5);
    const auto x = estimateMacroPixelPeriod(frame, true);
    if (x.period) {
      EXPECT_EQ(*x.period, 15) << brightness;
      found = true;
      continue;
    }
    if (x.plausible.empty() || unsure) continue;
    unsure = true;
    EXPECT_EQ(x.plausible.front(), 15) << brightness;
    ASSERT_TRUE(writeImage(dir / "faint.png", frame, {.sampleType = SampleType::UInt16}).ok());
    auto read = readLightField(dir / "faint.png");
    ASSERT_FALSE(read.ok());
    const std::string& message = read.error().message;
    EXPECT_EQ(read.error().code, ErrorCode::Usage);
    EXPECT_NE(message.find("faint.png"), std::string::npos) << message;
    EXPECT_NE(message.find("plausible across: 15"), std::string::npos) << message;
    EXPECT_NE(message.find("--lenslet-views"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_TRUE(found);
  EXPECT_TRUE(unsure);
}

TEST(MacroPixelPeriod, GivenViewsThatDoNotDivideTheImageAreAUsageError) {
  test::TempDir dir;
  ASSERT_TRUE(writeImage(dir / "frame.png", microscopeFrame({.views = 7, .lensesX = 30, .lensesY = 20}, 6),
                         {.sampleType = SampleType::UInt16})
                  .ok());
  auto read = readLightField(dir / "frame.png", {.lensletViews = 4});  // 210 x 140: 4 divides neither
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().code, ErrorCode::Usage);
  EXPECT_NE(read.error().message.find("frame.png"), std::string::npos) << read.error().message;
  auto probed = probeLightField(dir / "frame.png", {.lensletViews = 4});
  ASSERT_FALSE(probed.ok());
  EXPECT_EQ(probed.error().code, ErrorCode::Usage);
}

}  // namespace
}  // namespace lfcam
