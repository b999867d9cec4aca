// The black level of the real light-field microscope raw (../shared/data/lfm-guv): its TIFFs carry
// no level, and the camera offset is what its dark frame holds. Decoding with the dark frame's mean
// as the black level (what `--black-level N` gives) comes close to decoding with the dark frame;
// decoding with no level at all does not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/decode/decode.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

double psnr(const LightField& a, const LightField& b, double peak) {
  double sum = 0;
  for (std::size_t i = 0; i < a.samples().size(); ++i) {
    const double d = double(a.samples()[i]) - b.samples()[i];
    sum += d * d;
  }
  return 10 * std::log10(peak * peak * double(a.samples().size()) / sum);
}

TEST(LfmGuvBlackLevel, TheDarkFramesMeanAsBlackLevelDecodesCloseToTheDarkFrame) {
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", folder);
  auto dark = readRaw(folder / "DarkFrame_GUVExperim1.tif");
  ASSERT_TRUE(dark.ok()) << dark.error().message;
  EXPECT_EQ(dark->blackLevel, 0);  // no tag, no camera.json
  double offset = 0;
  for (const float value : dark->mosaic.pixels()) offset += value;
  offset /= double(dark->mosaic.pixels().size());
  const RawReadOptions withLevel{.blackLevel = offset};
  auto raw = readRaw(folder / "Lightfield_GUVExperim1.tif"), white = readRaw(folder / "Radiometry_GUVExperim1.tif");
  auto rawLevel = readRaw(folder / "Lightfield_GUVExperim1.tif", withLevel);
  auto whiteLevel = readRaw(folder / "Radiometry_GUVExperim1.tif", withLevel);
  ASSERT_TRUE(raw.ok() && white.ok() && rawLevel.ok() && whiteLevel.ok());
  auto grid = calibrateGrid(*whiteLevel, CalibrationOptions{}, "Radiometry_GUVExperim1.tif");
  ASSERT_TRUE(grid.ok()) << grid.error().message;

  DecodeOptions options{.white = &*white, .dark = &*dark};
  auto byDark = decodeLightField(*raw, *grid, options);
  options = {.white = &*whiteLevel};
  auto byLevel = decodeLightField(*rawLevel, *grid, options);
  options = {.white = &*white};
  auto none = decodeLightField(*raw, *grid, options);
  ASSERT_TRUE(byDark.ok() && byLevel.ok() && none.ok());
  float peak = 0;
  for (const float value : byDark->samples()) peak = std::max(peak, value);
  const double levelFigure = psnr(*byLevel, *byDark, peak), noneFigure = psnr(*none, *byDark, peak);
  std::printf(
      "[ black   ] lfm-guv: dark frame mean %.1f DN; against the dark-frame decode: PSNR %.2f dB with that "
      "black level, %.2f dB with none\n",
      offset, levelFigure, noneFigure);
  EXPECT_GT(offset, 1);
  EXPECT_GT(levelFigure, noneFigure + 10);
}

}  // namespace
}  // namespace lfcam
