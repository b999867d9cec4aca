// refocusUpsampled on the real Lytro flower (10x10 views of 256x256), an aliasing check by spectra.
// An image enlarged from a coarser one carries, beyond the coarse Nyquist frequency, copies of its
// low band (attenuated by the enlargement's filter): repeated pixels show as blocks, the aliasing
// artefact. The check measures that copy's energy in the upsampled photograph against repeated
// pixels of the plain one (and prints a bilinear enlargement's, the smooth kind).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <mutex>
#include <utility>

#include "core/fftw_planner.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/render/upsampled_refocus.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

// The mean of the channels, times a Hann window (so the frame's edges add no streaks to the spectrum).
Image windowedLuminance(const Image& photo) {
  Image out(photo.width(), photo.height(), 1);
  for (int y = 0; y < photo.height(); ++y)
    for (int x = 0; x < photo.width(); ++x) {
      double sum = 0;
      for (int c = 0; c < photo.channels(); ++c) sum += photo.at(x, y, c);
      const double wx = 0.5 - 0.5 * std::cos(2 * M_PI * (x + 0.5) / photo.width());
      const double wy = 0.5 - 0.5 * std::cos(2 * M_PI * (y + 0.5) / photo.height());
      out.at(x, y, 0) = float(sum / photo.channels() * wx * wy);
    }
  return out;
}

// The energy of the high band that is a copy of the low band, over the low band's energy, the
// largest over the three partners (half the sampling rate away along x, along y, and along both):
// in blocks of 8 x 8 bins of the low band (|fx|, |fy| < 1/4 cycle per pixel), the partner bins'
// spectrum fitted (least squares) by one complex multiple of the low bins' (a copy through a
// smooth filter, as an enlargement makes), the fit's energy summed over blocks.
double copiedEnergy(const Image& photo) {
  const int w = photo.width(), h = photo.height();
  const Image windowed = windowedLuminance(photo);
  std::unique_ptr<fftwf_complex[], fftw::Free> buffer(
      static_cast<fftwf_complex*>(fftwf_malloc(sizeof(fftwf_complex) * std::size_t(w) * h)));
  fftwf_plan plan;
  {
    const std::lock_guard<std::mutex> lock(fftw::plannerMutex());
    plan = fftwf_plan_dft_2d(h, w, buffer.get(), buffer.get(), FFTW_FORWARD, FFTW_ESTIMATE);
  }
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
    buffer[i][0] = windowed.pixels()[i];
    buffer[i][1] = 0;
  }
  fftwf_execute(plan);
  {
    const std::lock_guard<std::mutex> lock(fftw::plannerMutex());
    fftwf_destroy_plan(plan);
  }
  const auto bin = [&](int kx, int ky) {
    const fftwf_complex& c = buffer[std::size_t((ky + h) % h) * w + (kx + w) % w];
    return std::complex<double>(c[0], c[1]);
  };
  double worst = 0;
  for (auto [sx, sy] : {std::pair{w / 2, 0}, std::pair{0, h / 2}, std::pair{w / 2, h / 2}}) {
    double copied = 0, lowEnergy = 0;
    const int block = 8;
    for (int by = -h / 4; by < h / 4; by += block)
      for (int bx = -w / 4; bx < w / 4; bx += block) {
        std::complex<double> cross = 0;
        double low = 0;
        for (int ky = by; ky < by + block; ++ky)
          for (int kx = bx; kx < bx + block; ++kx) {
            const std::complex<double> a = bin(kx, ky), b = bin(kx + sx, ky + sy);
            cross += std::conj(a) * b;
            low += std::norm(a);
          }
        if (low > 0) copied += std::norm(cross) / low;
        lowEnergy += low;
      }
    worst = std::max(worst, copied / lowEnergy);
  }
  return worst;
}

// `photo` enlarged `factor` times by repeating pixels: all of its high band is a copy.
Image repeated(const Image& photo, int factor) {
  Image out(photo.width() * factor, photo.height() * factor, photo.channels());
  for (int c = 0; c < photo.channels(); ++c)
    for (int y = 0; y < out.height(); ++y)
      for (int x = 0; x < out.width(); ++x) out.at(x, y, c) = photo.at(x / factor, y / factor, c);
  return out;
}

// `photo` enlarged `factor` times by bilinear interpolation (pixel centres aligned, edges clamped).
Image bilinear(const Image& photo, int factor) {
  Image out(photo.width() * factor, photo.height() * factor, photo.channels());
  for (int c = 0; c < photo.channels(); ++c)
    for (int y = 0; y < out.height(); ++y)
      for (int x = 0; x < out.width(); ++x) {
        const double fx = std::clamp((x + 0.5) / factor - 0.5, 0.0, photo.width() - 1.0),
                     fy = std::clamp((y + 0.5) / factor - 0.5, 0.0, photo.height() - 1.0);
        const int x0 = std::min(int(fx), photo.width() - 2), y0 = std::min(int(fy), photo.height() - 2);
        const double ax = fx - x0, ay = fy - y0;
        out.at(x, y, c) = float((1 - ay) * ((1 - ax) * photo.at(x0, y0, c) + ax * photo.at(x0 + 1, y0, c)) +
                                ay * ((1 - ax) * photo.at(x0, y0 + 1, c) + ax * photo.at(x0 + 1, y0 + 1, c)));
      }
  return out;
}

TEST(LytroFlowerUpsampled, HighBandHoldsLittleCopyOfTheLowBand) {
  LFCAM_REQUIRE_SHARED_DATA("lytro-f01-flower", dir);
  auto lf = readLightField(dir);
  ASSERT_TRUE(lf) << lf.error().message;
  // -0.3: the near flowers in focus (README); -0.7: the ground behind them. At both the ten views'
  // shifts cover the sub-pixel phases. (At slope 0 they share one phase and the fine grid repeats
  // the plain pixels by design, upsampled_refocus_test.cpp.)
  for (double slope : {-0.3, -0.7}) {
    const Image plain = refocus(*lf, slope);
    auto fine = refocusUpsampled(*lf, slope, 2);
    ASSERT_TRUE(fine);
    const double upsampled = copiedEnergy(*fine), blocks = copiedEnergy(repeated(plain, 2));
    std::printf(
        "slope %.2f: copy of the low band in the high band, energy over the low band's: %.2e upsampled "
        "(K = 2), %.2e repeated pixels, %.2e bilinear enlargement\n",
        slope, upsampled, blocks, copiedEnergy(bilinear(plain, 2)));
    EXPECT_LT(upsampled, 0.25 * blocks) << "slope " << slope;
  }
}

}  // namespace
}  // namespace lfcam
