// Depth and all-in-focus speed on the HCI "antinous" light field (9x9 views, 512x512 RGB), with
// the scores of the depth map against its ground truth printed first.
//   BM_Refocus      one full-colour refocus: the floor, the unit of work of both operations.
//   BM_Depth        estimateDepth with default options. Counter ratio = time / refocus time.
//   BM_DepthWithoutFill  the same without the edge-aware fill (fillLambda = 0); counter
//                   fill_cost = default time / this time - 1, CPU time of both in this run
//                   (the time shown is of both runs).
//   BM_DepthSubsetsApart  estimateDepth with and without aggregateSubsetsApart, alternating;
//                   counter apart_cost = CPU time with / without - 1 (this run).
//   BM_DepthOcclusionEdges  the same for the occlusion-edge step (occlusionBand 0):
//                   occlusion_cost. These three also show cpu_default_s, CPU seconds per
//                   default run.
//   BM_AllInFocus   allInFocus given the depth map (focal stack + blending). Same counter.
//   BM_DepthAndAllInFocus  both, as `lfcam edof` without --depth does: the goal is < 5 s on 2 cores.
//
// Run: build-*/bench/depth_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <ctime>

#include "lfcam/all_in_focus.hpp"
#include "lfcam/depth.hpp"
#include "lfcam/disparity_scores.hpp"
#include "lfcam/image_io.hpp"
#include "lfcam/layered_planes.hpp"
#include "lfcam/light_field_io.hpp"
#include "lfcam/refocus.hpp"

namespace {

using lfcam::LightField;

const char* kFolder = LFCAM_SHARED_DATA_DIR "/hci-antinous";

const LightField& antinous() {
  static const LightField lightField = [] {
    auto read = lfcam::readLightField(kFolder);
    if (read) return std::move(read).value();
    std::fprintf(stderr, "depth_bench: cannot read %s (%s);\n  using a layered-planes light field of 9x9 views, 512x512\n",
                 kFolder, read.error().message.c_str());
    return std::move(lfcam::renderLayeredPlanes(lfcam::defaultLayeredPlanesScene(9, 512)).lightField);
  }();
  return lightField;
}

double refocusSeconds = 0;

void BM_Refocus(benchmark::State& state) {
  const LightField& lightField = antinous();
  double total = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(lfcam::refocus(lightField, 0.5));
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  refocusSeconds = total / double(state.iterations());
}

void reportRatio(benchmark::State& state, double seconds) {
  if (refocusSeconds > 0) state.counters["ratio_to_refocus"] = seconds / refocusSeconds;
}

void BM_Depth(benchmark::State& state) {
  const LightField& lightField = antinous();
  double total = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    auto depth = lfcam::estimateDepth(lightField);
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!depth) state.SkipWithError(depth.error().message.c_str());
  }
  reportRatio(state, total / double(state.iterations()));
}

// CPU time of the process (every thread): on a shared machine closer to the work done than wall time.
double processCpuSeconds() {
  return double(std::clock()) / CLOCKS_PER_SEC;
}

// Process CPU time of estimateDepth with `without` and with the default options, alternating
// (the state's iterations each run both); returns with / without - 1.
double extraCpuOfDefault(benchmark::State& state, const lfcam::DepthOptions& without) {
  const LightField& lightField = antinous();
  auto timeDepth = [&](const lfcam::DepthOptions& options) {
    const double start = processCpuSeconds();
    auto depth = lfcam::estimateDepth(lightField, options);
    if (!depth) state.SkipWithError(depth.error().message.c_str());
    return processCpuSeconds() - start;
  };
  double withSeconds = 0, withoutSeconds = 0;
  for (auto _ : state) {
    withSeconds += timeDepth({});
    withoutSeconds += timeDepth(without);
  }
  state.counters["cpu_default_s"] = withSeconds / double(state.iterations());
  return withoutSeconds > 0 ? withSeconds / withoutSeconds - 1 : 0.0;
}

void BM_DepthWithoutFill(benchmark::State& state) {
  state.counters["fill_cost"] = extraCpuOfDefault(state, {.fillLambda = 0.0});
}

void BM_DepthSubsetsApart(benchmark::State& state) {
  state.counters["apart_cost"] = extraCpuOfDefault(state, {.aggregateSubsetsApart = false});
}

// The occlusion-edge step (src/edof/occlusion_edges.cpp): CPU with it over without, same run.
void BM_DepthOcclusionEdges(benchmark::State& state) {
  state.counters["occlusion_cost"] = extraCpuOfDefault(state, {.occlusionBand = 0});
}

void BM_AllInFocus(benchmark::State& state) {
  const LightField& lightField = antinous();
  auto depth = lfcam::estimateDepth(lightField);
  if (!depth) return state.SkipWithError(depth.error().message.c_str());
  double total = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    auto photo = lfcam::allInFocus(lightField, {.disparity = &depth->disparity});
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!photo) state.SkipWithError(photo.error().message.c_str());
  }
  reportRatio(state, total / double(state.iterations()));
}

void BM_DepthAndAllInFocus(benchmark::State& state) {
  const LightField& lightField = antinous();
  for (auto _ : state) {
    auto depth = lfcam::estimateDepth(lightField);
    if (!depth) return state.SkipWithError(depth.error().message.c_str());
    auto photo = lfcam::allInFocus(lightField, {.disparity = &depth->disparity});
    if (!photo) return state.SkipWithError(photo.error().message.c_str());
  }
}

BENCHMARK(BM_Refocus)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_Depth)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_DepthWithoutFill)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_DepthSubsetsApart)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_DepthOcclusionEdges)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_AllInFocus)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_DepthAndAllInFocus)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// The depth map's scores against the ground truth, when it is there (depth.hpp).
void printScores() {
  auto truth = lfcam::readImage(std::string(kFolder) + "/gt_disp_lowres.pfm");
  if (!truth) return;
  const auto start = std::chrono::steady_clock::now();
  auto depth = lfcam::estimateDepth(antinous());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!depth) return;
  auto scores = lfcam::scoreDisparity(depth->disparity, *truth), fine = lfcam::scoreDisparity(depth->disparity, *truth, 0.03);
  if (scores && fine)
    std::printf("hci-antinous: BadPix(0.07) %.2f %%, BadPix(0.03) %.2f %%, MSE x100 %.3f (%d labels, %.2f s)\n",
                scores->badPix, fine->badPix, scores->mse100, depth->labels, seconds);
}

}  // namespace

int main(int argc, char** argv) {
  printScores();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
