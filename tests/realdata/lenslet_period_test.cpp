// The views per lens of real lenslet images that do not say them: napari-LF's rectified frame of
// the lfm-guv microscope capture, that capture decoded and written back at 15 and 19 pixels per
// lens into a mostly dark, noisy 16-bit frame, and the Lytro flower as a colour lenslet image.
// Photographs and the unrectified raw frame are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/decode/decode.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

void expectViews(const fs::path& path, int nu, int nv, int ns, int nt, int channels) {
  const auto start = std::chrono::steady_clock::now();
  auto info = probeLightField(path);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info->format, LightFieldFormat::LensletImage);
  EXPECT_EQ(info->shape, (LightFieldShape{.nu = nu, .nv = nv, .ns = ns, .nt = nt, .channels = channels}))
      << path.filename();
  std::printf("[ period  ] %s: %dx%d views per lens found, probe (read and estimate) %.0f ms\n",
              path.filename().c_str(), info->shape.nu, info->shape.nv, ms);
}

TEST(LensletPeriodRealData, NapariRectifiedMicroscopeFrame) {
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", folder);
  // A 448 x 432 16-bit TIFF named .png: 16 pixels per lens, 28 x 27 lenses.
  expectViews(folder / "reference_outputs_napariLF" / "LightfieldRectified.png", 16, 16, 28, 27, 1);
}

// The light field embedded at lens (s0, t0) of a lensesX x lensesY frame of dark background with
// Gaussian noise, 16-bit, without lfcam's description.
fs::path darkFrame(const LightField& lf, int lensesX, int lensesY, int s0, int t0, double noiseLevel,
                   const fs::path& path) {
  float peak = 0;
  for (float value : lf.samples()) peak = std::max(peak, value);
  Image image(lensesX * lf.nu(), lensesY * lf.nv(), lf.channels());
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0.0, noiseLevel);
  for (int c = 0; c < lf.channels(); ++c)
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        const int s = x / lf.nu() - s0, t = y / lf.nv() - t0;
        double value = 0.01 + noise(random);
        if (s >= 0 && t >= 0 && s < lf.ns() && t < lf.nt())
          value += 0.3 / peak * lf.at(x % lf.nu(), y % lf.nv(), s, t, c);
        image.at(x, y, c) = float(std::clamp(value, 0.0, 1.0));
      }
  EXPECT_TRUE(writeImage(path, image, {.sampleType = SampleType::UInt16}).ok());
  return path;
}

TEST(LensletPeriodRealData, DecodedMicroscopeCaptureInADarkNoisyFrame) {
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", folder);
  // Monochrome 16-bit frames, with the dark frame for black.
  const auto frame = [&](const char* name) {
    return readRaw(folder / name, {.colorFilter = ColorFilter::Mono, .blackLevel = 0, .whiteLevel = 65535});
  };
  auto raw = frame("Lightfield_GUVExperim1.tif"), white = frame("Radiometry_GUVExperim1.tif");
  auto dark = frame("DarkFrame_GUVExperim1.tif");
  ASSERT_TRUE(raw.ok() && white.ok() && dark.ok());
  auto grid = calibrateGrid(*white, {}, "Radiometry_GUVExperim1.tif");
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  test::TempDir dir;
  // 15 views (the lenses' 15.4 pixels), and 19 (resampled): 77 x 67 lenses, the 28 x 28 of the
  // capture in a corner of darkness; 1155 x 1005 and 1463 x 1273 pixels.
  for (int views : {15, 19}) {
    SCOPED_TRACE(views);
    DecodeOptions options;
    options.white = &*white;
    options.dark = &*dark;
    options.views = views;
    auto lf = decodeLightField(*raw, *grid, options);
    ASSERT_TRUE(lf.ok()) << lf.error().message;
    ASSERT_EQ(lf->nu(), views);
    const fs::path path = dir / ("guv" + std::to_string(views) + ".png");
    expectViews(darkFrame(*lf, 77, 67, 30, 20, 0.01, path), views, views, 77, 67, 1);
    expectViews(darkFrame(*lf, 77, 67, 30, 20, 0.02, path), views, views, 77, 67, 1);
    expectViews(darkFrame(*lf, lf->ns(), lf->nt(), 0, 0, 0.0, path), views, views, lf->ns(), lf->nt(), 1);
  }
}

TEST(LensletPeriodRealData, LytroFlowerAsAColorLensletImage) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-f01-flower", folder);
  auto lf = readLightField(folder / "views");
  ASSERT_TRUE(lf.ok()) << lf.error().message;
  test::TempDir dir;
  // 2560 x 2560, 10 pixels per lens: 2, 4, 5, 8, 16, 20 ... divide the size too.
  expectViews(darkFrame(*lf, lf->ns(), lf->nt(), 0, 0, 0.02, dir / "flower.png"), 10, 10, 256, 256, 3);
}

TEST(LensletPeriodRealData, PhotographsAndTheRawFrameAreRefused) {
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", guv);
  LFCAM_REQUIRE_SHARED_DATA("hci-antinous", hci);
  LFCAM_REQUIRE_SHARED_DATA("lytro-f01-flower", lytro);
  test::TempDir dir;
  auto view = readImage(hci / "input_Cam040.png");
  ASSERT_TRUE(view.ok());
  ASSERT_TRUE(writeImage(dir / "antinous.jpg", *view).ok());
  for (const fs::path& path : {guv / "Lightfield_GUVExperim1.tif", hci / "input_Cam040.png", dir / "antinous.jpg",
                               lytro / "views" / "IMG_0001_055_06_06.png"}) {
    auto info = probeLightField(path);
    ASSERT_FALSE(info.ok()) << path;
    EXPECT_EQ(info.error().code, ErrorCode::Usage) << path;
    EXPECT_NE(info.error().message.find("--lenslet-views"), std::string::npos) << info.error().message;
  }
}

}  // namespace
}  // namespace lfcam
