// Decoding a raw lenslet image made from real views (HCI "antinous", ../shared/data/hci-antinous),
// laid out as a camera stores its raw (decode.hpp): the scene upright in the lenslet layout,
// microlens (i, j) holding sample (s, t) = (i, j), view u lying u - (nu - 1) / 2 pixels right of
// the microlens image's centre. Decoding gives the views back as the raw holds them, not turned.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lfcam/decode/decode.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

// PSNR (peak 1) of decoded view (u, v) against the true view (tu, tv), turned by 180 degrees in
// (s, t) or not, over the samples two away from the border.
double viewPsnr(const LightField& decoded, int u, int v, const LightField& truth, int tu, int tv, bool turned) {
  const int ns = decoded.ns(), nt = decoded.nt();
  double sum = 0;
  long count = 0;
  for (int t = 2; t < nt - 2; ++t)
    for (int s = 2; s < ns - 2; ++s) {
      const int ts = turned ? ns - 1 - s : s, tt = turned ? nt - 1 - t : t;
      const double d = decoded.at(u, v, s, t, 0) - truth.at(tu, tv, ts, tt, 0);
      sum += d * d, ++count;
    }
  return 10 * std::log10(1.0 / std::max(sum / count, 1e-20));
}

TEST(DecodeHciLenslet, ViewsComeBackAsTheRawHoldsThem) {
  LFCAM_REQUIRE_SHARED_DATA("hci-antinous", folder);
  auto views = readLightField(folder);
  ASSERT_TRUE(views) << views.error().message;
  const int n = views->nu(), crop = 96;
  const int s0 = (views->ns() - crop) / 2, t0 = (views->nt() - crop) / 2;
  LightField truth(LightFieldShape{n, n, crop, crop, 1});  // the grey of a centre crop
  for (int v = 0; v < n; ++v)
    for (int u = 0; u < n; ++u)
      for (int t = 0; t < crop; ++t)
        for (int s = 0; s < crop; ++s) {
          double grey = 0;
          for (int c = 0; c < views->channels(); ++c) grey += views->at(u, v, s0 + s, t0 + t, c);
          truth.at(u, v, s, t, 0) = float(grey / views->channels());
        }

  // The raw: square grid of 11.37 px turned by 0.4 degrees; each pixel takes the views at its
  // offset from its microlens image's centre (bilinear between views), dark beyond them.
  LensletGrid grid;
  grid.pitchX = grid.pitchY = 11.37;
  grid.rotationRad = 0.4 * M_PI / 180;
  grid.origin = {8.3, 7.9};
  grid.columns = grid.rows = crop;
  const int size = int(std::ceil(crop * grid.pitchX + 16));
  RawImage raw;
  raw.mosaic = Image(size, size, 1);
  raw.colorFilter = ColorFilter::Mono;
  raw.whiteLevel = 1;
  const double cs = std::cos(grid.rotationRad), sn = std::sin(grid.rotationRad), middle = 0.5 * (n - 1);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double dx = x + 0.5 - grid.origin[0], dy = y + 0.5 - grid.origin[1];
      const int i = int(std::lround((cs * dx + sn * dy) / grid.pitchX)),
                j = int(std::lround((-sn * dx + cs * dy) / grid.pitchY));
      if (i < 0 || j < 0 || i >= crop || j >= crop) continue;
      const auto centre = grid.centre(i, j);
      const double u = middle + x + 0.5 - centre[0], v = middle + y + 0.5 - centre[1];
      if (u < 0 || v < 0 || u > n - 1 || v > n - 1) continue;
      const int u0 = std::min(int(u), n - 2), v0 = std::min(int(v), n - 2);
      const double fu = u - u0, fv = v - v0;
      raw.mosaic.at(x, y, 0) =
          float((1 - fv) * ((1 - fu) * truth.at(u0, v0, i, j, 0) + fu * truth.at(u0 + 1, v0, i, j, 0)) +
                fv * ((1 - fu) * truth.at(u0, v0 + 1, i, j, 0) + fu * truth.at(u0 + 1, v0 + 1, i, j, 0)));
    }

  DecodeOptions options;
  options.views = n;
  options.repairHotPixels = false;
  auto decoded = decodeLightField(raw, grid, options);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  ASSERT_EQ(decoded->shape(), truth.shape());
  const int c = n / 2, side = c + 3;
  const double centreAsHeld = viewPsnr(*decoded, c, c, truth, c, c, false);
  const double centreTurned = viewPsnr(*decoded, c, c, truth, c, c, true);
  // An off-centre view: the same view of the truth, or the one on the other side of the lens.
  const double sideSame = viewPsnr(*decoded, side, c, truth, side, c, false);
  const double sideMirrored = viewPsnr(*decoded, side, c, truth, n - 1 - side, c, false);
  std::printf(
      "[ decode  ] lenslet raw of hci-antinous (11.37 px, 0.4 deg): centre view PSNR %.2f dB against the "
      "true centre view as the raw holds it, %.2f dB turned by 180 degrees; view u = %d: %.2f dB against "
      "the same view, %.2f dB against view %d\n",
      centreAsHeld, centreTurned, side, sideSame, sideMirrored, n - 1 - side);
  EXPECT_GT(centreAsHeld, 40.0);
  EXPECT_GT(centreAsHeld, centreTurned + 10.0);
  EXPECT_GT(sideSame, 35.0);
  EXPECT_GT(sideSame, sideMirrored + 5.0);
}

}  // namespace
}  // namespace lfcam
