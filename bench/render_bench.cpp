// The synthetic camera's kernels (synthetic_camera.hpp, fourier_slice.hpp) on a layered-planes
// light field of 9x9 views of 256x256 RGB, each as a ratio to the plain refocus of the same field
// measured in the same run (style.md, point 8). `lfcam bench` compares them with the memory floor.
//
// Run: build-*/bench/render_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <optional>

#include "lfcam/render/fourier_slice.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/render/synthetic_camera.hpp"
#include "lfcam/synth/layered_planes.hpp"

namespace {

const lfcam::LightField& field() {
  static const lfcam::LightField lightField =
      std::move(lfcam::renderLayeredPlanes(lfcam::defaultLayeredPlanesScene(9, 256)).lightField);
  return lightField;
}

double seconds(const auto& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Plain refocus, best of 5: the denominator of every ratio.
double refocusSeconds() {
  static const double best = [] {
    double b = 1e30;
    for (int i = 0; i < 5; ++i)
      b = std::min(b, seconds([] { benchmark::DoNotOptimize(lfcam::refocus(field(), 0.63)); }));
    return b;
  }();
  return best;
}

template <class Work>
void run(benchmark::State& state, const Work& work) {
  const double denominator = refocusSeconds();  // also builds the light field, outside the timing
  double total = 0;
  for (auto _ : state) total += seconds(work);
  state.counters["ratio_to_refocus"] = total / double(state.iterations()) / denominator;
}

void BM_Refocus(benchmark::State& state) {
  run(state, [] { benchmark::DoNotOptimize(lfcam::refocus(field(), 0.63)); });
}
BENCHMARK(BM_Refocus)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_CircularAperture(benchmark::State& state) {
  run(state, [] {
    benchmark::DoNotOptimize(
        lfcam::renderSyntheticPhoto(field(), {.slope = 0.63, .aperture = lfcam::Aperture::circle(2.5)}));
  });
}
BENCHMARK(BM_CircularAperture)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Quadrature(benchmark::State& state) {
  const int supersampling = int(state.range(0));
  run(state, [&] {
    benchmark::DoNotOptimize(lfcam::renderSyntheticPhoto(
        field(), {.slope = 2.5}, {.method = lfcam::RenderMethod::Quadrature, .supersampling = supersampling}));
  });
}
BENCHMARK(BM_Quadrature)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Observer(benchmark::State& state) {
  run(state, [] { benchmark::DoNotOptimize(lfcam::observe(field(), {.u = 0.5, .v = -1.25})); });
}
BENCHMARK(BM_Observer)->Unit(benchmark::kMillisecond)->UseRealTime();

// Per photograph, after the 4D FFT (counter setup_s: that FFT, once).
void BM_FourierSlice(benchmark::State& state) {
  field();
  double setup = 0;
  std::optional<lfcam::FourierRefocuser> refocuser;
  setup = seconds([&] { refocuser.emplace(std::move(*lfcam::FourierRefocuser::create(field()))); });
  run(state, [&] { benchmark::DoNotOptimize(refocuser->refocus(0.63)); });
  state.counters["setup_s"] = setup;
}
BENCHMARK(BM_FourierSlice)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
