// Fourier slice refocusing against the spatial-domain refocus: the same photographs, away from
// the borders (the Fourier method wraps around), to a PSNR threshold.
#include "lfcam/render/fourier_slice.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/render/refocus.hpp"
#include "lfcam/render/synthetic_camera.hpp"
#include "lfcam/synth/layered_planes.hpp"

namespace lfcam {
namespace {

// PSNR (peak 1) over the pixels at least `margin` from every border.
double interiorPsnr(const Image& a, const Image& b, int margin) {
  double squares = 0;
  long count = 0;
  for (int c = 0; c < a.channels(); ++c)
    for (int y = margin; y < a.height() - margin; ++y)
      for (int x = margin; x < a.width() - margin; ++x) {
        const double d = double(a.at(x, y, c)) - b.at(x, y, c);
        squares += d * d, ++count;
      }
  return 10 * std::log10(1.0 / (squares / count));
}

TEST(FourierSlice, SlopeZeroIsTheMeanOfTheViews) {
  const LightField lightField = std::move(renderLayeredPlanes(defaultLayeredPlanesScene(5, 48)).lightField);
  auto refocuser = FourierRefocuser::create(lightField);
  ASSERT_TRUE(refocuser);
  const Image fourier = refocuser->refocus(0.0);
  const Image spatial = refocus(lightField, 0.0);
  EXPECT_GT(interiorPsnr(fourier, spatial, 0), 60.0);
}

TEST(FourierSlice, MatchesTheSpatialQuadratureAwayFromTheBorders) {
  const LightField lightField = std::move(renderLayeredPlanes(defaultLayeredPlanesScene(7, 64)).lightField);
  auto refocuser = FourierRefocuser::create(lightField);
  ASSERT_TRUE(refocuser) << refocuser.error().message;
  for (double slope : {-1.0, 0.5, 1.6}) {
    const Image fourier = refocuser->refocus(slope);
    // The Fourier slice interpolates between views (band-limited): compare with the quadrature.
    auto quadrature =
        renderSyntheticPhoto(lightField, {.slope = slope}, {.method = RenderMethod::Quadrature, .supersampling = 4});
    ASSERT_TRUE(quadrature);
    const int margin = int(std::ceil(std::abs(slope) * 3)) + 2;
    const double psnr = interiorPsnr(fourier, *quadrature, margin);
    std::printf("slope %.2f: PSNR Fourier slice vs quadrature %.1f dB\n", slope, psnr);
    // Measured 40.4, 42.7 and 26.8 dB: the two quadratures differ most where the views are
    // farthest apart in the image (sinc against tent interpolation between views).
    EXPECT_GT(psnr, std::abs(slope) <= 1 ? 36.0 : 24.0) << "slope " << slope;
  }
  EXPECT_FALSE(FourierRefocuser::create(LightField()));
}

}  // namespace
}  // namespace lfcam
