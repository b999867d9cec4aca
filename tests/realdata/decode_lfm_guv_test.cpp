// Decoding the real light-field microscope raw (../shared/data/lfm-guv): monochrome, square grid of
// about 15.38 px, with its white (radiometry) image and dark frame.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "lenslet_means.hpp"
#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/decode/decode.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

struct LfmGuv {
  RawImage raw, white, dark;
  LensletGrid grid;
};

// The capture, its white image and dark frame, and the grid calibrated from the white image.
void readLfmGuv(const std::filesystem::path& folder, LfmGuv& out) {
  RawReadOptions read;
  read.colorFilter = ColorFilter::Mono;
  read.blackLevel = 0;
  read.whiteLevel = 65535;
  auto raw = readRaw(folder / "Lightfield_GUVExperim1.tif", read);
  auto white = readRaw(folder / "Radiometry_GUVExperim1.tif", read);
  auto dark = readRaw(folder / "DarkFrame_GUVExperim1.tif", read);
  ASSERT_TRUE(raw.ok() && white.ok() && dark.ok());
  auto grid = calibrateGrid(*white, CalibrationOptions{}, "Radiometry_GUVExperim1.tif");
  ASSERT_TRUE(grid.ok()) << grid.error().message;
  out = {std::move(*raw), std::move(*white), std::move(*dark), *grid};
}

Result<LightField> decodeLfmGuv(const LfmGuv& data) {
  DecodeOptions options;
  options.white = &data.white;
  options.dark = &data.dark;
  return decodeLightField(data.raw, data.grid, options);
}

TEST(DecodeLfmGuv, ViewsArePlausible) {
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", folder);
  LfmGuv data;
  ASSERT_NO_FATAL_FAILURE(readLfmGuv(folder, data));
  const LensletGrid& grid = data.grid;
  EXPECT_NEAR(grid.pitchX, 15.38, 0.15);

  auto lf = decodeLfmGuv(data);
  ASSERT_TRUE(lf.ok()) << lf.error().message;
  EXPECT_EQ(lf->channels(), 1);
  EXPECT_EQ(lf->nu(), 15);
  EXPECT_GE(lf->ns(), 26);

  // Weights: in [0, 1], high at the aperture centre, low in the corner views.
  auto meanWeight = [&](int u, int v) {
    double sum = 0;
    const float* w = lf->weightPlane(u, v);
    for (std::size_t k = 0; k < lf->shape().viewPixels(); ++k) sum += w[k];
    return sum / double(lf->shape().viewPixels());
  };
  for (float w : lf->weights()) ASSERT_TRUE(w >= 0 && w <= 1);
  const int centre = lf->nu() / 2;
  const double centreWeight = meanWeight(centre, centre), cornerWeight = meanWeight(0, 0);
  EXPECT_GT(centreWeight, 0.6);
  EXPECT_LT(cornerWeight, centreWeight);

  // The centre view has structure (the vesicle), not a flat or noisy field.
  const Image view = lf->subApertureImage(centre, centre);
  double sum = 0, sumSquares = 0, neighbour = 0;
  long count = 0;
  for (int t = 1; t < view.height() - 1; ++t)
    for (int s = 1; s < view.width() - 1; ++s) {
      const double value = view.at(s, t, 0);
      ASSERT_TRUE(std::isfinite(value));
      sum += value, sumSquares += value * value, ++count;
      neighbour += std::abs(value - view.at(s + 1, t, 0));
    }
  const double mean = sum / count, deviation = std::sqrt(std::max(0.0, sumSquares / count - mean * mean));
  std::printf(
      "[ decode  ] lfm-guv: grid %dx%d pitch %.3f x %.3f px, rotation %.4f deg; centre view mean %.4f, "
      "std %.4f, mean |dx| %.4f; weight centre %.3f corner %.3f\n",
      grid.columns, grid.rows, grid.pitchX, grid.pitchY, grid.rotationRad * 180 / M_PI, mean, deviation,
      neighbour / count, centreWeight, cornerWeight);
  EXPECT_GT(mean, 0);
  EXPECT_GT(deviation / mean, 0.05);              // structure
  EXPECT_LT(neighbour / count, 2.0 * deviation);  // smoother than noise
}

// A photo decoded the right way up matches the raw's lenslet means (lenslet_means.hpp) as they
// lie; one turned upside down matches them only once turned by 180 degrees.
TEST(DecodeLfmGuv, CentreViewLiesAsTheLensletsDo) {
  LFCAM_REQUIRE_SHARED_DATA("lfm-guv", folder);
  LfmGuv data;
  ASSERT_NO_FATAL_FAILURE(readLfmGuv(folder, data));
  auto lf = decodeLfmGuv(data);
  ASSERT_TRUE(lf.ok()) << lf.error().message;
  ASSERT_EQ(lf->ns(), data.grid.columns);
  ASSERT_EQ(lf->nt(), data.grid.rows);
  const test::LensletMeans lenslets = test::lensletMeans(data.raw, data.white, data.grid, &data.dark);
  const int centre = lf->nu() / 2;
  const Image view = lf->subApertureImage(centre, centre);
  const int w = view.width(), h = view.height();
  // Over the microlenses wholly inside the raw, as they lie and turned.
  test::Correlation asTheyLie, turned;
  for (int t = 0; t < h; ++t)
    for (int s = 0; s < w; ++s) {
      if (!lenslets.complete[std::size_t(t) * w + s] || !lenslets.complete[std::size_t(h - 1 - t) * w + w - 1 - s])
        continue;
      asTheyLie.add(view.at(s, t, 0), lenslets.means.at(s, t, 0));
      turned.add(view.at(w - 1 - s, h - 1 - t, 0), lenslets.means.at(s, t, 0));
    }
  std::printf(
      "[ decode  ] lfm-guv: centre view against the raw's lenslet means: correlation %.3f as they lie, "
      "%.3f turned by 180 degrees\n",
      asTheyLie.value(), turned.value());
  EXPECT_GT(asTheyLie.value(), 0.85);
  EXPECT_GT(asTheyLie.value(), turned.value() + 0.1);
}

}  // namespace
}  // namespace lfcam
