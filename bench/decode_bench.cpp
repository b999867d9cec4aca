// Decode speed on a raw of a Lytro Illum's size (7728 x 5368 GRBG photosites, hexagonal lattice of
// 14.29 px, 14 x 14 views of about 541 x 433 microlenses), synthesised analytically (a vignetted
// disc under each microlens, modulated by a pattern that varies across and within microlenses):
//   BM_DecodeIllum          the default decode (Malvar-He-Cutler, sub-pixel sampling, white image).
//                           Counters: peak_rss_mb (getrusage ru_maxrss of the whole process so
//                           far, which includes the two input raws), mpix_per_s of raw.
//   BM_DecodeIllumIntegral  the paper's integral-pitch sampling, same inputs.
//   BM_DecodeIllumHA        Hamilton-Adams demosaicing.
//   BM_DecodeIllumLightField  the light-field-aware demosaic, each decode followed (untimed) by a
//                           default one: ratio = its decode time / Malvar-He-Cutler's, and
//                           demosaic_ratio the same for the demosaic step alone (the raw's mosaic).
//   BM_DemosaicReference    the plain per-pixel demosaic against the fast one on a 1024 x 1024
//                           crop: ratio = reference time / fast time.
//   BM_SamplingReference    the same for the sampling (decode with the reference kernels on a crop).
// Goal (issue 4): under 3 s on 2 cores.
//
// Run: build-*/bench/decode_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <chrono>
#include <cmath>

#include "core/parallel.hpp"
#include "decode/decode_internal.hpp"
#include "lfcam/decode/decode.hpp"

namespace {

using namespace lfcam;

constexpr int kWidth = 7728, kHeight = 5368;
constexpr double kPitch = 14.29, kRotation = 0.0021;

LensletGrid illumGrid(int width, int height) {
  LensletGrid grid;
  grid.packing = Packing::Hexagonal;
  grid.pitchX = kPitch;
  grid.pitchY = kPitch * std::sqrt(3.0) / 2;
  grid.rotationRad = kRotation;
  grid.origin = {kPitch * 0.7, kPitch * 0.6};
  grid.columns = int((width - 1.5 * kPitch) / kPitch);
  grid.rows = int((height - 1.5 * kPitch) / grid.pitchY);
  return grid;
}

struct Synthetic {
  RawImage raw, white;
  LensletGrid grid;
};

// White: a disc of diameter 0.95 pitch under each microlens with a soft edge and a slow vignetting
// across the sensor; raw: the white times a texture of the microlens position and the offset in it.
Synthetic synthesise(int width, int height) {
  Synthetic out;
  out.grid = illumGrid(width, height);
  out.raw.mosaic = Image(width, height, 1);
  out.white.mosaic = Image(width, height, 1);
  for (RawImage* r : {&out.raw, &out.white}) {
    r->colorFilter = ColorFilter::GRBG;
    r->blackLevel = 64;
    r->whiteLevel = 1023;
  }
  const LensletGrid& g = out.grid;
  const double cs = std::cos(g.rotationRad), sn = std::sin(g.rotationRad);
  parallelFor(0, std::size_t(height), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < width; ++x) {
        const double dx = x + 0.5 - g.origin[0], dy = y + 0.5 - g.origin[1];
        const double a = (cs * dx + sn * dy) / g.pitchX, b = (-sn * dx + cs * dy) / g.pitchY;
        double best = 1e30, ex = 0, ey = 0;
        int bi = 0, bj = 0;
        for (int j = int(std::floor(b)); j <= int(std::floor(b)) + 1; ++j) {
          const double shift = (j & 1) ? 0.5 : 0.0;
          const int i = int(std::floor(a - shift + 0.5));
          const double ea = (a - shift - i) * g.pitchX, eb = (b - j) * g.pitchY;
          if (ea * ea + eb * eb < best) best = ea * ea + eb * eb, ex = ea, ey = eb, bi = i, bj = j;
        }
        const double r = std::sqrt(best) / (0.475 * kPitch);
        const double disc = std::clamp((1.0 - r) * 6.0, 0.0, 1.0);
        const double vignetting =
            1.0 - 0.3 * ((x - width / 2.0) * (x - width / 2.0) + (y - height / 2.0) * (y - height / 2.0)) /
                      (0.25 * (double(width) * width + double(height) * height));
        const double white = 800 * disc * vignetting;
        const double texture = 0.5 + 0.4 * std::sin(0.21 * bi + 0.05 * ex) * std::cos(0.17 * bj - 0.04 * ey);
        out.white.mosaic.at(x, y, 0) = float(std::round(64 + white));
        out.raw.mosaic.at(x, y, 0) = float(std::round(64 + white * texture));
      }
  });
  return out;
}

const Synthetic& illum() {
  static const Synthetic s = synthesise(kWidth, kHeight);
  return s;
}

double peakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

void runDecode(benchmark::State& state, DemosaicMethod method, Sampling sampling) {
  const Synthetic& s = illum();
  DecodeOptions options;
  options.white = &s.white;
  options.demosaic = method;
  options.sampling = sampling;
  for (auto _ : state) {
    auto lf = decodeLightField(s.raw, s.grid, options);
    if (!lf) state.SkipWithError(lf.error().message.c_str());
    benchmark::DoNotOptimize(lf);
  }
  state.counters["peak_rss_mb"] = peakRssMb();
  state.counters["mpix_per_s"] =
      benchmark::Counter(double(kWidth) * kHeight * 1e-6 * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_DecodeIllum(benchmark::State& state) { runDecode(state, DemosaicMethod::MalvarHeCutler, Sampling::SubPixel); }
void BM_DecodeIllumIntegral(benchmark::State& state) {
  runDecode(state, DemosaicMethod::MalvarHeCutler, Sampling::IntegralPitch);
}
void BM_DecodeIllumHA(benchmark::State& state) { runDecode(state, DemosaicMethod::HamiltonAdams, Sampling::SubPixel); }

template <class F>
double seconds(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_DecodeIllumLightField(benchmark::State& state) {
  const Synthetic& s = illum();
  DecodeOptions options;
  options.white = &s.white;
  double aware = 0, malvar = 0, awareStep = 0, malvarStep = 0;
  for (auto _ : state) {
    options.demosaic = DemosaicMethod::LightFieldAware;
    aware += seconds([&] { benchmark::DoNotOptimize(decodeLightField(s.raw, s.grid, options)); });
    state.PauseTiming();
    options.demosaic = DemosaicMethod::MalvarHeCutler;
    malvar += seconds([&] { benchmark::DoNotOptimize(decodeLightField(s.raw, s.grid, options)); });
    awareStep += seconds([&] {
      benchmark::DoNotOptimize(demosaic(s.raw.mosaic, ColorFilter::GRBG, DemosaicMethod::LightFieldAware, &s.grid));
    });
    malvarStep += seconds(
        [&] { benchmark::DoNotOptimize(demosaic(s.raw.mosaic, ColorFilter::GRBG, DemosaicMethod::MalvarHeCutler)); });
    state.ResumeTiming();
  }
  state.counters["ratio"] = aware / malvar;
  state.counters["demosaic_ratio"] = awareStep / malvarStep;
  state.counters["peak_rss_mb"] = peakRssMb();
}

void BM_DemosaicReference(benchmark::State& state) {
  static const Synthetic s = synthesise(1024, 1024);
  Image mosaic = s.raw.mosaic.copy();
  for (auto _ : state) {
    const double fast =
        seconds([&] { benchmark::DoNotOptimize(demosaic(mosaic, ColorFilter::GRBG, DemosaicMethod::MalvarHeCutler)); });
    const double reference = seconds([&] {
      benchmark::DoNotOptimize(
          decode_detail::demosaicReference(mosaic, ColorFilter::GRBG, DemosaicMethod::MalvarHeCutler));
    });
    state.counters["ratio"] = reference / fast;
  }
}

void BM_SamplingReference(benchmark::State& state) {
  static const Synthetic s = synthesise(1024, 1024);
  DecodeOptions options;
  options.white = &s.white;
  for (auto _ : state) {
    const double fast = seconds([&] { benchmark::DoNotOptimize(decodeLightField(s.raw, s.grid, options)); });
    const double reference = seconds([&] {
      benchmark::DoNotOptimize(
          decode_detail::decodeLightField(s.raw, s.grid, options, decode_detail::Kernels::Reference));
    });
    state.counters["ratio"] = reference / fast;
  }
}

}  // namespace

BENCHMARK(BM_DecodeIllum)->Unit(benchmark::kMillisecond)->Iterations(2)->UseRealTime();
BENCHMARK(BM_DecodeIllumLightField)->Unit(benchmark::kMillisecond)->Iterations(2)->UseRealTime();
BENCHMARK(BM_DecodeIllumIntegral)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_DecodeIllumHA)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_DemosaicReference)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_SamplingReference)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

BENCHMARK_MAIN();
