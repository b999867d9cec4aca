// The simulator's speed: rays per second per core on a small capture of the `people` scene with
// the prototype's optics, and (when LFCAM_BENCH_PAPER=1) the time of a paper-scale capture:
// 4000 x 4000 pixels, ~288 x 288 microlenses of 125 um, 16 samples per pixel (goal: < 30 s on
// 2 cores). The floor, measured in the same run: the same capture of the `white` scene, where a
// ray costs only the optics (no scene intersection), so the ratio shows what the scene costs.
#include <benchmark/benchmark.h>

#include <cstdlib>

#include "core/parallel.hpp"
#include "lfcam/simulate/simulate.hpp"

namespace {

using namespace lfcam;

void captureBenchmark(benchmark::State& state, const char* sceneName, int size, int threads) {
  setThreadCount(threads);
  const CameraModel camera = CameraModel::paperPrototype(size, size);
  const Scene scene = *builtinScene(sceneName, camera);
  std::uint64_t rays = 0;
  for (auto _ : state) {
    const SensorCapture capture = simulateCapture(scene, camera, {.samplesPerPixel = 16});
    rays += capture.rays;
    benchmark::DoNotOptimize(capture.raw.pixels().data());
  }
  state.counters["rays_per_s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
  if (threads > 0)
    state.counters["rays_per_s_per_thread"] = benchmark::Counter(double(rays) / threads, benchmark::Counter::kIsRate);
  setThreadCount(0);
}

// Per core: one thread.
void BM_SimulatePeopleOneThread(benchmark::State& state) { captureBenchmark(state, "people", 256, 1); }
void BM_SimulateWhiteOneThread(benchmark::State& state) { captureBenchmark(state, "white", 256, 1); }
// All cores.
void BM_SimulatePeopleAllThreads(benchmark::State& state) { captureBenchmark(state, "people", 512, 0); }

BENCHMARK(BM_SimulatePeopleOneThread)->Unit(benchmark::kMillisecond);  // CPU time: one core
BENCHMARK(BM_SimulateWhiteOneThread)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SimulatePeopleAllThreads)->Unit(benchmark::kMillisecond)->UseRealTime();

// The sensor model alone (shot noise, read noise, quantisation) on one core, per pixel.
void BM_ApplySensorOneThread(benchmark::State& state) {
  setThreadCount(1);
  Image irradiance(1000, 1000, 1);
  for (std::size_t k = 0; k < irradiance.pixels().size(); ++k) irradiance.pixels()[k] = 0.001f * float(k % 61);
  Sensor sensor;
  for (auto _ : state) {
    const Image raw = applySensor(irradiance, sensor);
    benchmark::DoNotOptimize(raw.pixels().data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(irradiance.pixels().size()));
  setThreadCount(0);
}
BENCHMARK(BM_ApplySensorOneThread)->Unit(benchmark::kMillisecond);

void BM_PaperScaleCapture(benchmark::State& state) { captureBenchmark(state, "people", 4000, 0); }

const bool paperScaleRegistered = [] {
  const char* enabled = std::getenv("LFCAM_BENCH_PAPER");
  if (enabled && std::string(enabled) == "1")
    benchmark::RegisterBenchmark("BM_PaperScaleCapture", BM_PaperScaleCapture)
        ->Unit(benchmark::kSecond)
        ->UseRealTime()
        ->Iterations(1);
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
