// The depth-range passband filter (denoise.hpp): the FFT path against its float64 reference on
// random light fields, the passband against its definition, a plane at a passband slope kept, and
// white noise reduced.
#include "lfcam/render/denoise.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "lfcam/edof/depth.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "people_camera.hpp"
#include "render/denoise_padding.hpp"
#include "render/references.hpp"
#include "sine_chart.hpp"

namespace lfcam {
namespace {

LightField randomLightField(const LightFieldShape& shape, unsigned seed) {
  LightField lightField(shape);
  std::mt19937 generator(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (float& sample : lightField.samples()) sample = uniform(generator);
  return lightField;
}

// A Lambertian plane of slope d: view (u, v) at (s, t) sees the texture at (s + u d, t + v d)
// (u, v from the centre). The texture is a few smooth sinusoids.
LightField planeLightField(int views, int size, double slope) {
  LightField lightField({.nu = views, .nv = views, .ns = size, .nt = size, .channels = 1});
  const double waves[4][4] = {{0.05, 0.02, 0.3, 0.0},
                              {-0.11, 0.07, 0.2, 1.0},
                              {0.21, -0.16, 0.1, 2.0},
                              {0.03, 0.27, 0.1, 0.5}};  // fx, fy (cycles per pixel), amplitude, phase
  for (int v = 0; v < views; ++v)
    for (int u = 0; u < views; ++u)
      for (int t = 0; t < size; ++t)
        for (int s = 0; s < size; ++s) {
          const double x = s + lightField.uFromCentre(u) * slope, y = t + lightField.vFromCentre(v) * slope;
          double value = 0.5;
          for (const auto& w : waves) value += w[2] * std::cos(2 * std::numbers::pi * (w[0] * x + w[1] * y) + w[3]);
          lightField.at(u, v, s, t, 0) = float(value);
        }
  return lightField;
}

// RMS difference of two light fields over the pixels at least `margin` from every border.
double interiorRms(const LightField& a, const LightField& b, int margin) {
  double squares = 0;
  long count = 0;
  for (int v = 0; v < a.nv(); ++v)
    for (int u = 0; u < a.nu(); ++u)
      for (int c = 0; c < a.channels(); ++c)
        for (int t = margin; t < a.nt() - margin; ++t)
          for (int s = margin; s < a.ns() - margin; ++s) {
            const double d = double(a.at(u, v, s, t, c)) - b.at(u, v, s, t, c);
            squares += d * d, ++count;
          }
  return std::sqrt(squares / double(count));
}

TEST(Denoise, PassbandIsAGaussianOfTheDistanceToTheSlopeSegment) {
  const DenoiseOptions options{.slopeMin = -0.5, .slopeMax = 1.0, .bandwidth = 0.05};
  std::mt19937 generator(3);
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  for (int trial = 0; trial < 2000; ++trial) {
    const double fs = uniform(generator), ft = uniform(generator), fu = uniform(generator), fv = uniform(generator);
    // Direct: the smallest distance to the segment, sampled finely, over its copies a cycle apart.
    double nearest = INFINITY;
    for (int k = 0; k <= 3000; ++k) {
      const double d = options.slopeMin + (options.slopeMax - options.slopeMin) * k / 3000.0;
      for (int ky = -2; ky <= 2; ++ky)
        for (int kx = -2; kx <= 2; ++kx) nearest = std::min(nearest, std::hypot(fu + kx - d * fs, fv + ky - d * ft));
    }
    const double expected = std::exp(-nearest * nearest / (2 * 0.05 * 0.05));
    ASSERT_NEAR(denoisePassband(options, fs, ft, fu, fv), expected, 2e-3) << fs << " " << ft << " " << fu << " " << fv;
  }
  // On a surface's plane the passband is 1, far from it nearly 0.
  EXPECT_DOUBLE_EQ(denoisePassband(options, 0.3, -0.2, 0.3 * 0.7, -0.2 * 0.7), 1.0);
  EXPECT_LT(denoisePassband(options, 0.3, 0.0, -0.4, 0.3), 1e-6);
}

TEST(Denoise, MatchesTheReferenceOnRandomLightFields) {
  const LightFieldShape shapes[] = {{.nu = 3, .nv = 3, .ns = 7, .nt = 6, .channels = 1},
                                    {.nu = 4, .nv = 3, .ns = 6, .nt = 5, .channels = 2},
                                    {.nu = 2, .nv = 5, .ns = 9, .nt = 4, .channels = 1}};
  const DenoiseOptions options[] = {{.slopeMin = -0.5, .slopeMax = 0.8, .bandwidth = 0.06},
                                    {.slopeMin = 0.3, .slopeMax = 0.3, .bandwidth = 0.1},
                                    {.slopeMin = -1.2, .slopeMax = -0.2, .bandwidth = 0.04}};
  for (int k = 0; k < 3; ++k) {
    const LightField lightField = randomLightField(shapes[k], 7 + k);
    auto fast = denoise(lightField, options[k]);
    auto reference = denoiseReference(lightField, options[k]);
    ASSERT_TRUE(fast && reference);
    EXPECT_LT(interiorRms(*fast, *reference, 0), 1e-5) << "case " << k;
  }
}

// A plane passband keeps its plane exactly (but for the mirrored borders); a hyperfan keeps a plane
// inside its range nearly (measured: rms change 0.009-0.021 over all views, against the texture's
// rms 0.27; more near the ends of the range, where the few views spread its spectrum out of the
// passband).
TEST(Denoise, KeepsAPlaneInItsPassband) {
  const int views = 9, size = 64;
  for (double slope : {-0.8, 0.0, 0.45}) {
    const LightField plane = planeLightField(views, size, slope);
    const int margin = int(std::ceil(std::abs(slope) * (views - 1))) + 2;
    auto planar = denoise(plane, {.slopeMin = slope, .slopeMax = slope});
    auto hyperfan = denoise(plane, {.slopeMin = -1.0, .slopeMax = 0.5});
    auto elsewhere = denoise(plane, {.slopeMin = slope + 0.6, .slopeMax = slope + 1.0});
    ASSERT_TRUE(planar && hyperfan && elsewhere);
    const double planarError = interiorRms(*planar, plane, margin);
    const double hyperfanError = interiorRms(*hyperfan, plane, margin);
    const double outsideError = interiorRms(*elsewhere, plane, margin);
    std::printf("plane at slope %+.2f: rms change %.5f (plane passband), %.5f (hyperfan -1:0.5), %.4f (outside)\n",
                slope, planarError, hyperfanError, outsideError);
    EXPECT_LT(planarError, 0.001);
    EXPECT_LT(hyperfanError, 0.03);
    EXPECT_GT(outsideError, 2 * hyperfanError);  // a passband that misses the plane changes it more
  }
}

// The noise that passes (by linearity: filtered noisy minus filtered clean) against the noise added.
TEST(Denoise, ReducesWhiteNoise) {
  const int views = 9, size = 64;
  const LightField clean = planeLightField(views, size, 0.3);
  LightField noisy = clean.copy();
  std::mt19937 generator(5);
  std::normal_distribution<float> normal(0.0f, 0.05f);
  for (float& sample : noisy.samples()) sample += normal(generator);
  const DenoiseOptions options{.slopeMin = -0.5, .slopeMax = 0.5};
  auto filtered = denoise(noisy, options);
  auto filteredClean = denoise(clean, options);
  ASSERT_TRUE(filtered && filteredClean);
  const int margin = 6;
  const double before = interiorRms(noisy, clean, margin), after = interiorRms(*filtered, *filteredClean, margin);
  std::printf("white noise: rms %.4f before, %.4f after (%.2fx)\n", before, after, before / after);
  EXPECT_GT(before / after, 2.0);
}

// Sharpness in the passband: the simulator's sine chart (ideal light field, 9x9 equally sharp
// views) at slopes near both ends of the range -1:0.75, through the default passband. Every grating
// below the views' Nyquist frequency keeps its modulation within 5 % in the centre view and in the
// photo refocused on the chart (measured: 0.97-1.03 of before; with bandwidth 0.03, 0.84-0.97). A
// decoded capture's views can be less equally sharp; bench/denoise_bench.cpp measures those.
TEST(Denoise, KeepsTheModulationOfGratingsInThePassband) {
  CameraModel camera = test::peopleCamera();
  camera.mainLens.setImageSideFNumber(4);  // microlens images 9 pixels across: 9x9 views
  auto white = idealLightField(*builtinScene("white", camera), camera);
  ASSERT_TRUE(white) << white.error().message;
  const DenoiseOptions options{.slopeMin = -1.0, .slopeMax = 0.75};
  for (double slope : {-0.75, 0.5}) {
    auto chart = idealLightFieldBoxFiltered(
        test::sineChartScene(camera, *distanceFromDisparity(*white->metadata.optics, slope)), camera, 4);
    ASSERT_TRUE(chart) << chart.error().message;
    ASSERT_EQ(chart->nu(), 9);
    auto filtered = denoise(*chart, options);
    ASSERT_TRUE(filtered);
    const int u = (chart->nu() - 1) / 2, v = (chart->nv() - 1) / 2;
    const std::vector<double> centreBefore = test::modulationPerBand(chart->subApertureImage(u, v), 1);
    const std::vector<double> centreAfter = test::modulationPerBand(filtered->subApertureImage(u, v), 1);
    const std::vector<double> photoBefore = test::modulationPerBand(refocus(*chart, slope), 1);
    const std::vector<double> photoAfter = test::modulationPerBand(refocus(*filtered, slope), 1);
    for (std::size_t band = 0; band < test::kChartFrequencies.size(); ++band) {
      if (test::kChartFrequencies[band] > 0.5) continue;  // aliased in every view
      std::printf("slope %+.2f, %.2f cycles/px: centre view %.3f -> %.3f, refocused %.3f -> %.3f\n", slope,
                  test::kChartFrequencies[band], centreBefore[band], centreAfter[band], photoBefore[band],
                  photoAfter[band]);
      EXPECT_GT(centreAfter[band], 0.95 * centreBefore[band]) << "slope " << slope << ", band " << band;
      EXPECT_GT(photoAfter[band], 0.95 * photoBefore[band]) << "slope " << slope << ", band " << band;
    }
  }
}

TEST(Denoise, RefusesBadOptions) {
  const LightField lightField = randomLightField({.nu = 2, .nv = 2, .ns = 4, .nt = 4, .channels = 1}, 1);
  EXPECT_EQ(denoise(lightField, {.slopeMin = 1, .slopeMax = 0}).error().code, ErrorCode::Usage);
  EXPECT_EQ(denoise(lightField, {.slopeMin = NAN, .slopeMax = 0}).error().code, ErrorCode::Usage);
  EXPECT_EQ(denoise(lightField, {.bandwidth = 0}).error().code, ErrorCode::Usage);
  EXPECT_EQ(denoise(LightField{}, {}).error().code, ErrorCode::Usage);
}

TEST(Denoise, DefaultRangeIsTheStatedDisparityRange) {
  LightField lightField = randomLightField({.nu = 2, .nv = 2, .ns = 4, .nt = 4, .channels = 1}, 1);
  EXPECT_EQ(defaultDenoiseOptions(lightField).slopeMin, -2.0);
  lightField.metadata.disparityMin = -0.7;
  lightField.metadata.disparityMax = 1.1;
  EXPECT_EQ(defaultDenoiseOptions(lightField).slopeMin, -0.7);
  EXPECT_EQ(defaultDenoiseOptions(lightField).slopeMax, 1.1);
}

}  // namespace
}  // namespace lfcam
