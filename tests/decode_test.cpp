// Decoding raw lenslet images: fast kernels against their references, and decoded simulator
// captures against the simulator's ideal light field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

#include <cstdint>

#include "decode/decode_internal.hpp"
#include "lfcam/decode/decode.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "sharpness.hpp"
#include "simulate/simulated_grid.hpp"

namespace lfcam {
namespace {

Image randomImage(int w, int h, int channels, unsigned seed, float lo = 0, float hi = 1) {
  Image image(w, h, channels);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> dist(lo, hi);
  for (float& v : image.pixels()) v = dist(rng);
  return image;
}

double maxDifference(std::span<const float> a, std::span<const float> b) {
  double worst = 0;
  for (std::size_t k = 0; k < a.size(); ++k) worst = std::max(worst, double(std::abs(a[k] - b[k])));
  return worst;
}

TEST(Decode, FastDemosaicMatchesReference) {
  for (ColorFilter filter : {ColorFilter::RGGB, ColorFilter::BGGR, ColorFilter::GRBG, ColorFilter::GBRG})
    for (DemosaicMethod method : {DemosaicMethod::MalvarHeCutler, DemosaicMethod::HamiltonAdams}) {
      const Image mosaic = randomImage(37, 29, 1, 7 + int(filter));
      const Image fast = demosaic(mosaic, filter, method);
      const Image reference = decode_detail::demosaicReference(mosaic, filter, method);
      ASSERT_EQ(fast.channels(), 3);
      EXPECT_LT(maxDifference(fast.pixels(), reference.pixels()), 1e-5)
          << colorFilterName(filter) << " method " << int(method);
    }
}

TEST(Decode, DemosaicKeepsFlatColorsAndMeasuredSamples) {
  // A flat colour field: every method gives it back exactly; measured photosites are kept.
  const float rgb[3] = {0.2f, 0.5f, 0.8f};
  Image mosaic(16, 12, 1);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x) mosaic.at(x, y, 0) = rgb[colorFilterChannel(ColorFilter::GRBG, x, y)];
  LensletGrid grid;
  grid.pitchX = grid.pitchY = 5;
  grid.columns = 4, grid.rows = 3;
  grid.origin = {2.5, 2.5};
  for (DemosaicMethod method : {DemosaicMethod::MalvarHeCutler, DemosaicMethod::HamiltonAdams,
                                DemosaicMethod::LensletAware, DemosaicMethod::LightFieldAware}) {
    const Image out = demosaic(mosaic, ColorFilter::GRBG, method, &grid);
    for (int c = 0; c < 3; ++c)
      for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 16; ++x) ASSERT_NEAR(out.at(x, y, c), rgb[c], 1e-5) << int(method);
  }
}

TEST(Decode, LensletAwareDemosaicDoesNotCrossMicrolensBoundaries) {
  // Two microlenses side by side, one dark and one bright: no bright value leaks into the dark one.
  LensletGrid grid;
  grid.pitchX = grid.pitchY = 8;
  grid.columns = 2, grid.rows = 1;
  grid.origin = {4, 4};
  Image mosaic(16, 8, 1);
  for (int y = 0; y < 8; ++y)
    for (int x = 8; x < 16; ++x) mosaic.at(x, y, 0) = 1;
  const Image out = demosaic(mosaic, ColorFilter::RGGB, DemosaicMethod::LensletAware, &grid);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < 8; ++y) {
      EXPECT_EQ(out.at(7, y, c), 0.0f);
      EXPECT_EQ(out.at(8, y, c), 1.0f);
    }
  const Image mhc = demosaic(mosaic, ColorFilter::RGGB, DemosaicMethod::MalvarHeCutler);
  double leak = 0;
  for (int c = 0; c < 3; ++c) leak += std::abs(mhc.at(7, 3, c));
  EXPECT_GT(leak, 0.01);  // what the lenslet-aware method avoids
}

TEST(Decode, HotPixelsAreRepaired) {
  Image mosaic = randomImage(20, 20, 1, 3, 0.4f, 0.5f);
  mosaic.at(9, 10, 0) = 1.0f;
  EXPECT_EQ(repairHotPixels(mosaic, ColorFilter::RGGB, 0.25f), 1);
  EXPECT_LT(mosaic.at(9, 10, 0), 0.5f);
  EXPECT_GE(mosaic.at(9, 10, 0), 0.4f);
}

// The screened fast path against a plain reading of the rule, on spikes everywhere (borders too).
TEST(Decode, HotPixelRepairMatchesThePlainRule) {
  for (ColorFilter filter : {ColorFilter::RGGB, ColorFilter::Mono}) {
    Image mosaic = randomImage(41, 23, 1, 5, 0.3f, 0.6f);
    std::mt19937 rng(9);
    for (int k = 0; k < 60; ++k) mosaic.at(int(rng() % 41), int(rng() % 23), 0) = 0.95f;
    Image expected = mosaic.copy();
    const int step = filter == ColorFilter::Mono ? 1 : 2;
    int count = 0;
    for (int y = 0; y < 23; ++y)
      for (int x = 0; x < 41; ++x) {
        std::vector<float> around;
        for (int dy = -step; dy <= step; dy += step)
          for (int dx = -step; dx <= step; dx += step)
            if ((dx || dy) && x + dx >= 0 && y + dy >= 0 && x + dx < 41 && y + dy < 23)
              around.push_back(mosaic.at(x + dx, y + dy, 0));
        if (around.size() < 3 || mosaic.at(x, y, 0) <= *std::max_element(around.begin(), around.end()) + 0.25f)
          continue;
        std::nth_element(around.begin(), around.begin() + std::ptrdiff_t(around.size() / 2), around.end());
        expected.at(x, y, 0) = around[around.size() / 2];
        ++count;
      }
    ASSERT_GT(count, 10);
    EXPECT_EQ(repairHotPixels(mosaic, filter, 0.25f), count);
    EXPECT_EQ(maxDifference(mosaic.pixels(), expected.pixels()), 0.0);
  }
}

TEST(Decode, HexagonalRowsMoveOntoTheOtherRows) {
  // Row 1 samples a ramp at s + 1/2; after resampling it reads the ramp at s, like row 0.
  LightField lf(LightFieldShape{1, 1, 10, 2, 1});
  for (int s = 0; s < 10; ++s) lf.at(0, 0, s, 0, 0) = float(s), lf.at(0, 0, s, 1, 0) = float(s + 0.5);
  hexRowsToRectangular(lf, 1);
  for (int s = 2; s < 9; ++s) {
    EXPECT_FLOAT_EQ(lf.at(0, 0, s, 1, 0), float(s));
    EXPECT_FLOAT_EQ(lf.at(0, 0, s, 0, 0), float(s));
  }
}

// A small random raw with a hexagonal, rotated grid: fast and reference kernels agree.
TEST(Decode, FastSamplingMatchesReference) {
  for (Sampling sampling : {Sampling::SubPixel, Sampling::IntegralPitch}) {
    RawImage raw;
    raw.mosaic = randomImage(131, 97, 1, 11, 64, 4095);
    raw.colorFilter = ColorFilter::GRBG;
    raw.blackLevel = 64;
    raw.whiteLevel = 4095;
    LensletGrid grid;
    grid.packing = Packing::Hexagonal;
    grid.pitchX = 9.37, grid.pitchY = 9.37 * 0.866;
    grid.rotationRad = 0.012;
    grid.origin = {3.2, 4.1};  // the first microlenses hang over the edge
    grid.columns = 14, grid.rows = 12;
    grid.hexParity = 1;
    DecodeOptions options;
    const Image white = randomImage(131, 97, 1, 12, 0.3f, 1.0f);
    options.whiteImage = &white;
    options.sampling = sampling;
    options.views = 9;
    auto fast = decodeLightField(raw, grid, options);
    auto reference = decode_detail::decodeLightField(raw, grid, options, decode_detail::Kernels::Reference);
    ASSERT_TRUE(fast.ok() && reference.ok());
    ASSERT_EQ(fast->shape(), (LightFieldShape{9, 9, 14, 12, 3}));
    EXPECT_LT(maxDifference(fast->samples(), reference->samples()), 1e-4);
    EXPECT_LT(maxDifference(fast->weights(), reference->weights()), 1e-5);
  }
}

// The light-field-aware demosaic's precomputed taps against its plain bounds-checked ones, on
// random raws (square and hexagonal, rotated, a few unlit photosites), through the decoder.
TEST(Decode, LightFieldAwareDemosaicMatchesReference) {
  for (Packing packing : {Packing::Square, Packing::Hexagonal}) {
    RawImage raw;
    raw.mosaic = randomImage(131, 97, 1, 21, 64, 4095);
    raw.colorFilter = packing == Packing::Square ? ColorFilter::RGGB : ColorFilter::GBRG;
    raw.blackLevel = 64;
    raw.whiteLevel = 4095;
    LensletGrid grid;
    grid.packing = packing;
    grid.pitchX = 9.37, grid.pitchY = packing == Packing::Square ? 9.37 : 9.37 * 0.866;
    grid.rotationRad = -0.015;
    grid.origin = {3.2, 4.1};
    grid.columns = 14, grid.rows = 11;
    Image white = randomImage(131, 97, 1, 22, 0.3f, 1.0f);
    for (std::size_t k = 0; k < white.planeSize(); k += 7) white.plane(0)[k] = 0;  // unlit
    DecodeOptions options;
    options.whiteImage = &white;
    options.demosaic = DemosaicMethod::LightFieldAware;
    options.views = 9;
    auto fast = decodeLightField(raw, grid, options);
    auto reference = decode_detail::decodeLightField(raw, grid, options, decode_detail::Kernels::Reference);
    ASSERT_TRUE(fast.ok() && reference.ok());
    EXPECT_LT(maxDifference(fast->samples(), reference->samples()), 1e-4);
    options.demosaic = DemosaicMethod::MalvarHeCutler;
    auto malvar = decodeLightField(raw, grid, options);
    ASSERT_TRUE(malvar.ok());
    EXPECT_GT(maxDifference(fast->samples(), malvar->samples()), 0.01);  // the 4D estimates are used
  }
}

// The public reference of the light-field-aware demosaic (plain taps, whole-plane passes) against
// the fast fused one, without a weight (every photosite lit), rotated square and hexagonal grids.
TEST(Decode, LightFieldAwareDemosaicReferenceIsPublic) {
  for (Packing packing : {Packing::Square, Packing::Hexagonal}) {
    LensletGrid grid;
    grid.packing = packing;
    grid.pitchX = 7.6, grid.pitchY = packing == Packing::Square ? 7.6 : 7.6 * 0.866;
    grid.rotationRad = 0.02;
    grid.origin = {2.7, 3.3};
    grid.columns = 9, grid.rows = 8;
    const Image mosaic = randomImage(71, 61, 1, 31 + int(packing));
    const Image fast = demosaic(mosaic, ColorFilter::BGGR, DemosaicMethod::LightFieldAware, &grid);
    const Image reference =
        decode_detail::demosaicReference(mosaic, ColorFilter::BGGR, DemosaicMethod::LightFieldAware, &grid);
    const Image malvar = decode_detail::demosaicReference(mosaic, ColorFilter::BGGR, DemosaicMethod::MalvarHeCutler);
    EXPECT_LT(maxDifference(fast.pixels(), reference.pixels()), 1e-4);
    EXPECT_GT(maxDifference(reference.pixels(), malvar.pixels()), 0.01);  // not Malvar-He-Cutler's
  }
}

// A flat scene under discs of light with dark gaps between them: every sample the white image lights
// reads the flat value, also at the rim, where the cubic's and the demosaicing's taps reach into
// the gaps (were the unlit photosites left at 0, they would pull those samples off by a few %).
TEST(Decode, UnlitPhotositesDoNotBiasTheRim) {
  for (ColorFilter filter : {ColorFilter::Mono, ColorFilter::RGGB}) {
    LensletGrid grid;
    grid.pitchX = grid.pitchY = 12.6;
    grid.rotationRad = 0.01;
    grid.origin = {7.3, 6.9};
    grid.columns = grid.rows = 8;
    RawImage white, raw;
    white.mosaic = Image(110, 110, 1);
    raw.mosaic = Image(110, 110, 1);
    for (RawImage* r : {&white, &raw}) r->colorFilter = filter, r->blackLevel = 64, r->whiteLevel = 4095;
    for (int y = 0; y < 110; ++y)
      for (int x = 0; x < 110; ++x) {
        double nearest = 1e9;
        for (int j = 0; j < grid.rows; ++j)
          for (int i = 0; i < grid.columns; ++i) {
            const auto c = grid.centre(i, j);
            nearest = std::min(nearest, std::hypot(x + 0.5 - c[0], y + 0.5 - c[1]));
          }
        const float lit = nearest < 0.45 * grid.pitchX ? 3000.0f : 0.0f;
        white.mosaic.at(x, y, 0) = 64 + lit;
        raw.mosaic.at(x, y, 0) = 64 + 0.5f * lit;
      }
    DecodeOptions options;
    options.white = &white;
    options.views = 11;
    auto lf = decodeLightField(raw, grid, options);
    ASSERT_TRUE(lf.ok()) << lf.error().message;
    double worst = 0;
    long rim = 0;
    for (int v = 0; v < lf->nv(); ++v)
      for (int u = 0; u < lf->nu(); ++u)
        for (int t = 1; t < lf->nt() - 1; ++t)
          for (int s = 1; s < lf->ns() - 1; ++s) {
            const float w = lf->weightPlane(u, v)[std::size_t(t) * lf->ns() + s];
            if (w < 0.5f) continue;
            rim += w < 0.99f;
            for (int c = 0; c < lf->channels(); ++c) worst = std::max(worst, std::abs(lf->at(u, v, s, t, c) - 0.5));
          }
    EXPECT_GT(rim, 100);  // the rim is tested
    EXPECT_LT(worst, 1e-4) << colorFilterName(filter);
  }
}

TEST(Decode, RejectsMismatchedInputs) {
  RawImage raw;
  raw.mosaic = Image(40, 30, 1);
  raw.whiteLevel = 1;
  LensletGrid grid;
  grid.pitchX = grid.pitchY = 10;
  grid.columns = 4, grid.rows = 3;
  DecodeOptions options;
  const Image white(41, 30, 1);
  options.whiteImage = &white;
  auto result = decodeLightField(raw, grid, options);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::Usage);
  EXPECT_NE(result.error().message.find("white image"), std::string::npos);
  EXPECT_FALSE(decodeLightField(raw, LensletGrid{}, {}).ok());
}

// ---- Simulated captures against the ideal light field.

struct SimulatedCase {
  const char* name;
  Packing packing;
  double pitchPx;  // of the microlens images on the sensor
  double rotationDeg;
  std::array<double, 2> offsetMm;
  ColorFilter filter;
  int size;  // sensor pixels across and down
};

CameraModel caseCamera(const SimulatedCase& c) {
  CameraModel camera = CameraModel::paperPrototype(c.size, c.size);
  MicrolensArray& m = *camera.microlenses;
  m.packing = c.packing;
  m.rotationDeg = c.rotationDeg;
  m.offsetMm = c.offsetMm;
  // The pixel pitch that makes the microlens images c.pitchPx pixels apart.
  const double scale = 1.0 + m.separationMm() / camera.mainLens.imageDistanceMm();
  camera.sensor.pixelPitchMm = m.pitchMm * scale / c.pitchPx;
  camera.sensor.colorFilter = c.filter;
  camera.sensor.noise = false;
  return camera;
}

RawImage rawOf(const Image& mosaic, const Sensor& sensor) {
  RawImage raw;
  raw.mosaic = mosaic.copy();
  raw.colorFilter = sensor.colorFilter;
  raw.blackLevel = sensor.blackLevel;
  raw.whiteLevel = sensor.whiteLevel;
  raw.source = "simulator";
  return raw;
}

struct Capture {
  CameraModel camera;
  RawImage raw, white;
  LensletGrid grid;
};

// Cards of smooth value noise (features several microlens footprints wide) at four depths, in
// front of and behind the plane of focus: content the light field's spatial sampling can hold, so
// the score measures the decoder rather than the aliasing of a point-sampled ideal.
Scene smoothScene(const CameraModel& camera) {
  Scene scene;
  scene.name = "smooth cards";
  scene.camera = camera;
  scene.background = {0.5f, 0.6f, 0.7f};
  const double d = camera.mainLens.focusDistanceMm, F = camera.mainLens.imageDistanceMm();
  const double half = 0.5 * camera.sensor.widthMm(), pitch = camera.microlenses->pitchMm;
  auto card = [&](double z, double x, double y, double size, double features, std::uint64_t seed) {
    Plane plane;
    plane.centreMm = {x * half * z / F, y * half * z / F, z};
    plane.widthMm = plane.heightMm = size * half * z / F;
    plane.texture.kind = TextureKind::Noise;
    plane.texture.periodMm = features * pitch * z / F;
    plane.texture.seed = seed;
    plane.texture.dark = {0.1f, 0.2f, 0.3f};
    plane.texture.light = {0.9f, 0.8f, 0.6f};
    return plane;
  };
  scene.planes = {card(2 * d, 0, 0, 3, 8, 1), card(1.3 * d, 0.5, -0.3, 0.8, 6, 2), card(d, -0.2, 0.1, 0.9, 5, 3),
                  card(0.85 * d, -0.5, 0.5, 0.6, 6, 4)};
  return scene;
}

Result<Scene> testScene(const std::string& name, const CameraModel& camera) {
  if (name == "smooth") return smoothScene(camera);
  return builtinScene(name, camera);
}

Capture simulate(const SimulatedCase& c, const std::string& sceneName) {
  Capture out;
  out.camera = caseCamera(c);
  SimulationOptions sim;
  sim.samplesPerPixel = 16;
  auto scene = testScene(sceneName, out.camera);
  auto white = builtinScene("white", out.camera);
  EXPECT_TRUE(scene.ok() && white.ok());
  out.raw = rawOf(simulateCapture(*scene, out.camera, sim).raw, out.camera.sensor);
  out.white = rawOf(simulateCapture(*white, out.camera, sim).raw, out.camera.sensor);
  out.grid = gridFromCamera(out.camera);
  return out;
}

// PSNR of `decoded` against `ideal` over the samples the ideal has inside the aperture and the
// decoded light field trusts (weight >= 0.5), the peak being the ideal's largest value there.
struct Score {
  double psnr = 0;
  double coverage = 0;  // share of the ideal's inside samples that were scored
};

Score score(const LightField& decoded, const LightField& ideal) {
  EXPECT_EQ(decoded.shape(), ideal.shape());
  if (!(decoded.shape() == ideal.shape())) return {};
  double sum = 0, peak = 0;
  long count = 0, inside = 0;
  for (int v = 0; v < ideal.nv(); ++v)
    for (int u = 0; u < ideal.nu(); ++u)
      for (int t = 0; t < ideal.nt(); ++t)
        for (int s = 0; s < ideal.ns(); ++s) {
          const std::size_t k = std::size_t(t) * ideal.ns() + s;
          if (ideal.weightPlane(u, v)[k] < 1) continue;
          ++inside;
          if (decoded.weightPlane(u, v)[k] < 0.5f) continue;
          for (int c = 0; c < ideal.channels(); ++c) {
            const double d = decoded.at(u, v, s, t, c) - ideal.at(u, v, s, t, c);
            sum += d * d;
            peak = std::max(peak, double(ideal.at(u, v, s, t, c)));
          }
          ++count;
        }
  Score result;
  result.coverage = inside ? double(count) / inside : 0;
  const double mse = sum / std::max(1.0, double(count) * ideal.channels());
  result.psnr = 10 * std::log10(peak * peak / std::max(mse, 1e-20));
  return result;
}

// The box-filtered ideal light field: one sample is the point-sampled field; on a uniform scene the
// footprint's mean is the point value.
TEST(IdealLightFieldBoxFiltered, AgreesWithThePointSampledFieldWhereItMust) {
  const SimulatedCase c{"square", Packing::Square, 13.37, 0.5, {0.01, 0.0}, ColorFilter::RGGB, 120};
  const CameraModel camera = caseCamera(c);
  for (const char* name : {"people", "white"}) {
    auto scene = builtinScene(name, camera);
    ASSERT_TRUE(scene.ok());
    auto point = idealLightField(*scene, camera);
    auto one = idealLightFieldBoxFiltered(*scene, camera, 1);
    auto four = idealLightFieldBoxFiltered(*scene, camera, 4);
    ASSERT_TRUE(point.ok() && one.ok() && four.ok());
    EXPECT_EQ(maxDifference(one->samples(), point->samples()), 0.0) << name;
    EXPECT_EQ(maxDifference(four->weights(), point->weights()), 0.0) << name;
    const double filtered = maxDifference(four->samples(), point->samples());
    if (std::string(name) == "white")
      EXPECT_LT(filtered, 1e-5);
    else
      EXPECT_GT(filtered, 0.01);  // textured: the footprint's mean differs from its centre
  }
}

// Asserted PSNR floors against the box-filtered ideal (docs/design.md, "Decoding", has the figures:
// 35.45 dB mono, 29.34 and 29.06 dB with a Bayer mosaic, where demosaicing costs the most; 32.34
// and 32.32 dB with the light-field-aware demosaic).
constexpr double kMonoPsnr = 34.0, kColorPsnr = 27.5, kLightFieldAwarePsnr = 31.0;
// A perfect demosaic (the true colour at every photosite): 35.15 and 34.74 dB.
constexpr double kCeilingPsnr = 33.5;

class DecodeSimulated : public ::testing::TestWithParam<SimulatedCase> {};

TEST_P(DecodeSimulated, MatchesTheIdealLightField) {
  const SimulatedCase& c = GetParam();
  const Capture capture = simulate(c, "smooth");
  auto scene = testScene("smooth", capture.camera);
  ASSERT_TRUE(scene.ok());
  // The fair reference: the ideal light field box-filtered over each sample's footprint (one
  // pixel in (u, v), one microlens in (s, t)), as the sensor integrates it; the point-sampled one
  // is scored too, for comparison.
  auto ideal = idealLightFieldBoxFiltered(*scene, capture.camera, 6);
  auto pointIdeal = idealLightField(*scene, capture.camera);
  ASSERT_TRUE(ideal.ok() && pointIdeal.ok());
  DecodeOptions options;
  options.white = &capture.white;
  options.views = ideal->nu();
  options.hexToRectangular = false;  // the ideal light field keeps the hexagonal rows
  auto decoded = decodeLightField(capture.raw, capture.grid, options);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  const Score subPixel = score(*decoded, *ideal);
  const Score pointSampled = score(*decoded, *pointIdeal);
  options.sampling = Sampling::IntegralPitch;
  auto integral = decodeLightField(capture.raw, capture.grid, options);
  ASSERT_TRUE(integral.ok());
  const Score paper = score(*integral, *ideal);
  std::printf(
      "[ decode  ] %s: PSNR %.2f dB sub-pixel against the box-filtered ideal (%.0f%% of the aperture's "
      "samples), %.2f dB against the point-sampled ideal; %.2f dB integral pitch\n",
      c.name, subPixel.psnr, 100 * subPixel.coverage, pointSampled.psnr, paper.psnr);
  EXPECT_GT(subPixel.psnr, c.filter == ColorFilter::Mono ? kMonoPsnr : kColorPsnr);
  if (c.filter != ColorFilter::Mono) {
    // The light-field-aware demosaic: the defocused cards' missing colours from the same view of
    // the neighbouring microlenses.
    DecodeOptions lightField = options;
    lightField.demosaic = DemosaicMethod::LightFieldAware;
    lightField.sampling = Sampling::SubPixel;
    auto aware = decodeLightField(capture.raw, capture.grid, lightField);
    ASSERT_TRUE(aware.ok());
    const Score awareScore = score(*aware, *ideal);
    std::printf("[ decode  ] %s: PSNR %.2f dB light-field-aware demosaic (%.2f dB Malvar-He-Cutler)\n", c.name,
                awareScore.psnr, subPixel.psnr);
    EXPECT_GT(awareScore.psnr, kLightFieldAwarePsnr);
    EXPECT_GT(awareScore.psnr, subPixel.psnr + 1.5);
  }
  EXPECT_GT(subPixel.psnr, pointSampled.psnr);
  EXPECT_GT(subPixel.coverage, 0.8);
  // Against the box-filtered ideal the paper's bilinear resampling gains a little on colour (its
  // extra smoothing hides some demosaicing error); sub-pixel sampling stays within 0.5 dB.
  EXPECT_GE(subPixel.psnr, paper.psnr - 0.5);
  if (c.packing == Packing::Hexagonal) {
    // Rectangular resampling: the same interpolation applied to the ideal light field.
    options.sampling = Sampling::SubPixel;
    options.hexToRectangular = true;
    auto rectangular = decodeLightField(capture.raw, capture.grid, options);
    ASSERT_TRUE(rectangular.ok());
    hexRowsToRectangular(*ideal, 1 - capture.grid.hexParity);
    const Score resampled = score(*rectangular, *ideal);
    std::printf("[ decode  ] %s: PSNR %.2f dB after hexagonal-to-rectangular resampling\n", c.name, resampled.psnr);
    EXPECT_GT(resampled.psnr, subPixel.psnr - 1.0);
  }
}

const SimulatedCase kSquareRggb{
    "square_13.37px_rot1_rggb", Packing::Square, 13.37, 1.0, {-0.02, 0.04}, ColorFilter::RGGB, 240};
const SimulatedCase kHexGrbg{
    "hex_13.37px_rot0.7_grbg", Packing::Hexagonal, 13.37, 0.7, {0.05, 0.01}, ColorFilter::GRBG, 240};

// The ceiling of any demosaic: the same scene simulated under all four Bayer layouts gives every
// photosite's true red, green and blue; devignetted and decoded exactly as a demosaiced mosaic (the
// decoder's steps before and after demosaicing), it scores what a perfect demosaic would. What it
// still loses is the sub-pixel sampling's (the mono case's figure), not the colour's.
TEST(DecodeSimulatedCeiling, PerfectDemosaicBoundsTheDemosaics) {
  for (const SimulatedCase& c : {kSquareRggb, kHexGrbg}) {
    const Capture capture = simulate(c, "smooth");
    auto scene = testScene("smooth", capture.camera);
    ASSERT_TRUE(scene.ok());
    auto ideal = idealLightFieldBoxFiltered(*scene, capture.camera, 6);
    ASSERT_TRUE(ideal.ok());
    DecodeOptions options;
    options.white = &capture.white;
    options.views = ideal->nu();
    options.hexToRectangular = false;
    auto malvar = decodeLightField(capture.raw, capture.grid, options);
    options.demosaic = DemosaicMethod::LightFieldAware;
    auto aware = decodeLightField(capture.raw, capture.grid, options);
    ASSERT_TRUE(malvar.ok() && aware.ok());

    // Every colour at every photosite, devignetted by its own layout's white image.
    const int w = capture.raw.mosaic.width(), h = capture.raw.mosaic.height();
    Image truth(w, h, 3);
    for (ColorFilter f : {ColorFilter::RGGB, ColorFilter::BGGR, ColorFilter::GRBG, ColorFilter::GBRG}) {
      SimulatedCase layout = c;
      layout.filter = f;
      std::optional<Capture> other;
      if (f != c.filter) other = simulate(layout, "smooth");
      const Capture& used = other ? *other : capture;
      DecodeOptions own = options;
      own.white = &used.white;
      auto devignetted = decode_detail::devignettedMosaic(used.raw, used.grid, own);
      ASSERT_TRUE(devignetted.ok());
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) truth.at(x, y, colorFilterChannel(f, x, y)) = devignetted->value.at(x, y, 0);
    }
    auto prepared = decode_detail::devignettedMosaic(capture.raw, capture.grid, options);
    ASSERT_TRUE(prepared.ok());
    auto perfect = decode_detail::decodeDemosaiced(std::move(truth), std::move(prepared->weight), capture.raw,
                                                   capture.grid, options);
    ASSERT_TRUE(perfect.ok()) << perfect.error().message;

    const double ceiling = score(*perfect, *ideal).psnr, lightField = score(*aware, *ideal).psnr,
                 mhc = score(*malvar, *ideal).psnr;
    std::printf(
        "[ decode  ] %s: PSNR %.2f dB perfect demosaic (the ceiling), %.2f dB light-field-aware, %.2f dB "
        "Malvar-He-Cutler\n",
        c.name, ceiling, lightField, mhc);
    EXPECT_GT(ceiling, kCeilingPsnr) << c.name;
    EXPECT_GT(ceiling, lightField + 1.0) << c.name;
    EXPECT_GT(lightField, mhc + 1.5) << c.name;
  }
}

// Section 6.3: sampling at the fitted sub-pixel centres removes the vernier error of the
// integral-pitch resampling, so refocusing onto the plane in focus is at least as sharp.
TEST(DecodeSimulatedRefocus, SubPixelIsAtLeastAsSharpAsIntegralPitch) {
  const SimulatedCase c{"square", Packing::Square, 13.37, 0.6, {0.02, 0.01}, ColorFilter::RGGB, 400};
  const Capture capture = simulate(c, "people");
  DecodeOptions options;
  options.white = &capture.white;
  auto subPixel = decodeLightField(capture.raw, capture.grid, options);
  options.sampling = Sampling::IntegralPitch;
  auto integral = decodeLightField(capture.raw, capture.grid, options);
  ASSERT_TRUE(subPixel.ok() && integral.ok());
  // The "focused person" card lies in the plane of focus: slope 0.
  const Image a = refocus(*subPixel, 0.0), b = refocus(*integral, 0.0);
  const int w = a.width(), h = a.height();
  const double sharpSub = test::laplacianVariance(a, w / 4, h / 4, 3 * w / 4, 3 * h / 4);
  const double sharpInt = test::laplacianVariance(b, w / 4, h / 4, 3 * w / 4, 3 * h / 4);
  std::printf("[ decode  ] refocus at slope 0: Laplacian variance %.5f sub-pixel, %.5f integral pitch (ratio %.3f)\n",
              sharpSub, sharpInt, sharpSub / sharpInt);
  EXPECT_GE(sharpSub, 0.98 * sharpInt);
}

// The refocus slope of a decoded capture means what it means for the ideal light field (and a
// view folder, the HCI convention of light_field.hpp): a card nearer than the plane of focus, at
// a known positive slope, comes into focus at that slope in both, and not at its opposite.
TEST(DecodeSimulatedRefocus, SlopeHasTheIdealLightFieldsSign) {
  const SimulatedCase c{"square", Packing::Square, 13.37, 0.4, {0.01, -0.02}, ColorFilter::Mono, 400};
  CameraModel camera = caseCamera(c);
  const double f = camera.mainLens.focalLengthMm, F = camera.mainLens.imageDistanceMm();
  const double z = 0.97 * camera.mainLens.focusDistanceMm;
  Scene scene;
  scene.camera = camera;
  Plane card;
  card.centreMm = {0, 0, z};
  card.widthMm = card.heightMm = 2 * camera.sensor.widthMm() * z / F;
  card.texture.kind = TextureKind::Noise;
  card.texture.periodMm = 2 * camera.microlenses->pitchMm * z / F;  // features two microlenses wide
  card.texture.seed = 5;
  scene.planes.push_back(card);
  auto white = builtinScene("white", camera);
  ASSERT_TRUE(white.ok());
  const SimulationOptions sim{.samplesPerPixel = 16};
  const RawImage raw = rawOf(simulateCapture(scene, camera, sim).raw, camera.sensor);
  const RawImage whiteRaw = rawOf(simulateCapture(*white, camera, sim).raw, camera.sensor);
  auto ideal = idealLightField(scene, camera);
  ASSERT_TRUE(ideal.ok());
  DecodeOptions options;
  options.white = &whiteRaw;
  options.views = ideal->nu();
  auto decoded = decodeLightField(raw, gridFromCamera(camera), options);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  // The card's slope: its image lies at F' = f z / (z - f) behind the lens, alpha = F' / F.
  const double known = ideal->metadata.optics->slopeFromAlpha(f * z / (z - f) / F);
  ASSERT_GT(known, 0.2);
  auto sharpness = [](const LightField& lf, double slope) {
    const Image photo = refocus(lf, slope);
    const int w = photo.width(), h = photo.height();
    return test::laplacianVariance(photo, w / 4, h / 4, 3 * w / 4, 3 * h / 4);
  };
  auto sharpest = [&](const LightField& lf) {
    double best = 0, bestSlope = 0;
    for (double slope = -1.0; slope <= 1.0 + 1e-9; slope += 0.05)
      if (const double value = sharpness(lf, slope); value > best) best = value, bestSlope = slope;
    return bestSlope;
  };
  const double decodedBest = sharpest(*decoded), idealBest = sharpest(*ideal);
  const double atKnown = sharpness(*decoded, known), atOpposite = sharpness(*decoded, -known);
  std::printf(
      "[ decode  ] card at slope %.3f: sharpest at %.2f decoded, %.2f ideal; decoded Laplacian variance "
      "%.5f at the slope, %.5f at its opposite\n",
      known, decodedBest, idealBest, atKnown, atOpposite);
  EXPECT_NEAR(idealBest, known, 0.1);
  EXPECT_NEAR(decodedBest, known, 0.1);
  EXPECT_GT(atKnown, 2 * atOpposite);
}

INSTANTIATE_TEST_SUITE_P(
    Configurations, DecodeSimulated,
    ::testing::Values(
        SimulatedCase{"square_13.37px_rot0.5_mono", Packing::Square, 13.37, 0.5, {0.03, -0.02}, ColorFilter::Mono, 240},
        kSquareRggb, kHexGrbg),
    [](const auto& param) {
      std::string name = param.param.name;
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

}  // namespace
}  // namespace lfcam
