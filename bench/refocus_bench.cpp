// Refocus speed, as ratios to floors measured in the same run (style.md, point 8):
// The floor (memory_floor.hpp) is measured before every timed run: floor_ms is its median, ratio
// the median of each run's time over its own floor.
//   BM_MemoryCopy         the copy that sets the floor; GB_per_s counts bytes read + written.
//   BM_MemoryRead         the antinous light field's samples read once by a threaded reduction
//                         (XOR of their bits, which the compiler vectorises): what reading alone
//                         reaches against the floor.
//   BM_Refocus            refocus of the HCI "antinous" light field (9x9 views, 512x512 RGB), or
//                         a layered-planes field of the same size when the data is absent.
//   BM_RefocusIllum       the same for a light field of a Lytro Illum's size (15x15 views of
//                         625x434 RGB, 732 MB), synthesised as layered planes, with its own floor.
//   BM_RefocusWeighted    the same field with a weight plane (a fifth of it 0), as a decoded raw.
//   BM_RefocusThreads     refocus of the antinous field on 1 and on 2 threads: the scaling.
//   BM_RefocusPages       refocus of the antinous field on huge pages (as LightField allocates it
//                         with LFCAM_HUGE_PAGES=1: run it so) and of a copy on 4 KiB pages
//                         (ratio = time / huge-page time, alternately).
//   BM_RefocusStack       a focal stack of the antinous field, 48 slopes 1/8 apart (all-in-focus's
//                         slices) in one call, against one call per slope (ratio, alternately).
//   BM_RefocusUpsampled   refocus on a grid K = 2, 3 times finer (upsampled_refocus.hpp) of the
//                         antinous field (ratio = its time / the plain refocus's, alternately).
//   BM_RefocusReference   the float64 oracle against the fast kernel on a smaller field
//                         (ratio = reference time / fast time).
//
// Run: build-*/bench/refocus_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>
#include <sys/prctl.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <vector>

#include "core/memory_floor.hpp"
#include "core/parallel.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/render/upsampled_refocus.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "render/references.hpp"

namespace {

using lfcam::LightField;

// A layered-planes field of the given size.
LightField layeredPlanes(int views, int width, int height = 0, int supersampling = 3) {
  lfcam::LayeredPlanesScene scene = lfcam::defaultLayeredPlanesScene(views, width, 1, height);
  scene.supersampling = supersampling;
  return std::move(lfcam::renderLayeredPlanes(scene).lightField);
}

// A light field of a Lytro Illum's size, made once (box filter off: only its size matters here).
const LightField& illum() {
  static const LightField lightField = layeredPlanes(15, 625, 434, 1);
  return lightField;
}

// The benchmark's light field, loaded once; the fallback says so on stderr.
const LightField& antinous() {
  static const LightField lightField = [] {
    const char* folder = LFCAM_SHARED_DATA_DIR "/hci-antinous";
    auto read = lfcam::readLightField(folder);
    if (read) return std::move(read).value();
    std::fprintf(stderr,
                 "refocus_bench: cannot read %s (%s);\n"
                 "  using a layered-planes light field of the same size (9x9 views, 512x512 RGB) instead\n",
                 folder, read.error().message.c_str());
    return layeredPlanes(9, 512);
  }();
  return lightField;
}

std::size_t bytesOf(const LightField& lightField) {
  return (lightField.samples().size() + lightField.weights().size()) * sizeof(float);
}

// The floor per byte, measured anew before every timed run (memory_floor.hpp).
lfcam::MemoryFloor& floorPerByte() {
  static lfcam::MemoryFloor floor(1.0);
  return floor;
}

// Each iteration measures the floor of `lightField`'s bytes (on all threads), then times `work`
// on `threads` threads (0: all), which is the iteration's time. Counters: floor_ms, the median
// floor, and ratio, the median of each run's time over its own floor.
template <class Work>
void timeAgainstFloor(benchmark::State& state, const LightField& lightField, const Work& work, int threads = 0) {
  std::vector<double> floors, ratios;
  for (auto _ : state) {
    const double floor = floorPerByte().measure() * double(bytesOf(lightField));
    lfcam::setThreadCount(threads);
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(work());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    lfcam::setThreadCount(0);
    state.SetIterationTime(seconds);
    floors.push_back(floor);
    ratios.push_back(seconds / floor);
  }
  state.counters["floor_ms"] = lfcam::medianOf(floors) * 1e3;
  state.counters["ratio"] = lfcam::medianOf(ratios);
}

void BM_MemoryCopy(benchmark::State& state) {
  std::vector<double> bandwidths;
  for (auto _ : state) {
    const double secondsPerByte = floorPerByte().measure();
    state.SetIterationTime(secondsPerByte * double(bytesOf(antinous())));
    bandwidths.push_back(1.0 / secondsPerByte);
  }
  state.counters["GB_per_s"] = lfcam::medianOf(bandwidths) / 1e9;  // read + written
}
BENCHMARK(BM_MemoryCopy)->Unit(benchmark::kMillisecond)->UseManualTime();

// Reads every sample of the light field once, over parallelFor's threads.
std::uint32_t readAll(const LightField& lightField) {
  const std::span<const float> samples = lightField.samples();
  const std::size_t slice = 1 << 20;
  std::vector<std::uint32_t> partial((samples.size() + slice - 1) / slice);
  lfcam::parallelFor(0, partial.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      std::uint32_t bits = 0;
      for (std::size_t k = i * slice; k < std::min(samples.size(), (i + 1) * slice); ++k)
        bits ^= std::bit_cast<std::uint32_t>(samples[k]);
      partial[i] = bits;
    }
  });
  std::uint32_t bits = 0;
  for (std::uint32_t p : partial) bits ^= p;
  return bits;
}

void BM_MemoryRead(benchmark::State& state) {
  timeAgainstFloor(state, antinous(), [] { return readAll(antinous()); });
}
BENCHMARK(BM_MemoryRead)->Unit(benchmark::kMillisecond)->UseManualTime();

void BM_Refocus(benchmark::State& state) {
  const LightField& lightField = antinous();
  const double slope = double(state.range(0)) / 100.0;
  timeAgainstFloor(state, lightField, [&] { return lfcam::refocus(lightField, slope).pixels().data(); });
  state.SetLabel(lightField.metadata.source.empty() ? "hci-antinous" : lightField.metadata.source);
}
// Slopes in hundredths: 0 (whole-pixel shifts), fractional ones, and one that moves the outer
// views 6 pixels.
BENCHMARK(BM_Refocus)->Arg(0)->Arg(-37)->Arg(63)->Arg(150)->Unit(benchmark::kMillisecond)->UseManualTime();

void BM_RefocusIllum(benchmark::State& state) {
  const LightField& lightField = illum();
  timeAgainstFloor(state, lightField, [&] { return lfcam::refocus(lightField, 0.63).pixels().data(); });
  state.SetLabel("15x15x625x434 RGB");
}
BENCHMARK(BM_RefocusIllum)->Unit(benchmark::kMillisecond)->UseManualTime();

// The antinous field with a weight plane, as a decoded raw has (refocus.hpp: each tap weighs its
// bilinear coefficient times the weight): a fifth of the samples weigh 0, as between microlenses,
// the rest a weight in (0, 1]. Its floor counts the weights' bytes too.
const LightField& antinousWeighted() {
  static const LightField lightField = [] {
    LightField copy = antinous().copy();
    copy.enableWeight();
    std::uint32_t state = 2005;
    for (float& weight : copy.weights()) {
      state = state * 1664525u + 1013904223u;  // a linear congruential sequence: cheap, fixed
      const std::uint32_t high = state >> 24;  // uniform in [0, 255]
      weight = high < 51 ? 0.0f : float(high) / 255.0f;
    }
    return copy;
  }();
  return lightField;
}

void BM_RefocusWeighted(benchmark::State& state) {
  const LightField& lightField = antinousWeighted();
  timeAgainstFloor(state, lightField, [&] { return lfcam::refocus(lightField, 0.63).pixels().data(); });
  state.SetLabel("antinous with a weight plane");
}
BENCHMARK(BM_RefocusWeighted)->Unit(benchmark::kMillisecond)->UseManualTime();

// Threads as the argument.
void BM_RefocusThreads(benchmark::State& state) {
  const LightField& lightField = antinous();
  timeAgainstFloor(
      state, lightField, [&] { return lfcam::refocus(lightField, 0.63).pixels().data(); }, int(state.range(0)));
}
BENCHMARK(BM_RefocusThreads)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();

// Runs `work` once per benchmark iteration and returns the mean seconds per run.
template <class Work>
double secondsPerRun(benchmark::State& state, const Work& work) {
  double seconds = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    lfcam::Image photo = work();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(photo.pixels().data());
  }
  return seconds / double(state.iterations());
}

// Argument K: refocusUpsampled at factor K (upsampled_refocus.hpp) against the plain refocus of
// the antinous field at the same slope, timed one after the other in each iteration; ratio is the
// median of upsampled time / plain time (goal for K = 2: at most 4, the viewer's budget).
void BM_RefocusUpsampled(benchmark::State& state) {
  const LightField& lightField = antinous();
  const int factor = int(state.range(0));
  std::vector<double> ratios;
  for (auto _ : state) {
    auto start = std::chrono::steady_clock::now();
    lfcam::Image plain = lfcam::refocus(lightField, 0.63);
    const double plainSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(plain.pixels().data());
    start = std::chrono::steady_clock::now();
    auto fine = lfcam::refocusUpsampled(lightField, 0.63, factor);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(fine->pixels().data());
    state.SetIterationTime(seconds);
    ratios.push_back(seconds / plainSeconds);
  }
  state.counters["ratio"] = lfcam::medianOf(ratios);
}
BENCHMARK(BM_RefocusUpsampled)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseManualTime();

// A copy of the antinous field on 4 KiB pages: made while the process refuses transparent huge
// pages, which overrides the allocator's advice.
const LightField& antinousOnSmallPages() {
  static const LightField lightField = [] {
    prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0);
    LightField copy = antinous().copy();
    prctl(PR_SET_THP_DISABLE, 0, 0, 0, 0);
    return copy;
  }();
  return lightField;
}

// Argument 1: the field on huge pages, 0: on small pages. Each iteration times both, so the
// ratio compares the two under the same conditions.
void BM_RefocusPages(benchmark::State& state) {
  const LightField& timed = state.range(0) ? antinous() : antinousOnSmallPages();
  const LightField& other = state.range(0) ? antinousOnSmallPages() : antinous();
  double timedSeconds = 0, otherSeconds = 0;
  for (auto _ : state) {
    for (const LightField* lightField : {&timed, &other}) {
      const auto start = std::chrono::steady_clock::now();
      lfcam::Image photo = lfcam::refocus(*lightField, 0.63);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      (lightField == &timed ? timedSeconds : otherSeconds) += seconds;
      benchmark::DoNotOptimize(photo.pixels().data());
    }
  }
  state.counters["ratio"] = state.range(0) ? 1.0 : timedSeconds / otherSeconds;
  state.SetLabel(state.range(0) ? "huge pages" : "4 KiB pages");
}
BENCHMARK(BM_RefocusPages)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// Ratio = time of the stack / time of one refocus per slope.
void BM_RefocusStack(benchmark::State& state) {
  const LightField& lightField = antinous();
  std::vector<double> slopes;
  for (int k = 0; k < 48; ++k) slopes.push_back(-3.0 + k / 8.0);
  double stackSeconds = 0, singleSeconds = 0;
  for (auto _ : state) {
    auto start = std::chrono::steady_clock::now();
    std::vector<lfcam::Image> stack = lfcam::refocus(lightField, slopes);
    stackSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(stack.back().pixels().data());
    start = std::chrono::steady_clock::now();
    for (double slope : slopes) {
      lfcam::Image photo = lfcam::refocus(lightField, slope);
      benchmark::DoNotOptimize(photo.pixels().data());
    }
    singleSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  state.counters["ratio"] = stackSeconds / singleSeconds;
  state.counters["stack_ms"] = 1e3 * stackSeconds / state.iterations();
}
BENCHMARK(BM_RefocusStack)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// The fast kernel against the reference on one smaller light field (5x5 views, 128x128 RGB).
const LightField& small() {
  static const LightField lightField = layeredPlanes(5, 128);
  return lightField;
}

void BM_RefocusSmall(benchmark::State& state) {
  small();  // made once, outside the timing
  const double perRun = secondsPerRun(state, [] { return lfcam::refocus(small(), 0.63); });
  state.counters["MP_per_s"] = 128.0 * 128.0 / 1e6 / perRun;
}
BENCHMARK(BM_RefocusSmall)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RefocusReference(benchmark::State& state) {
  // The fast kernel's best of 20 on the same field, for the ratio.
  double fast = 1e30;
  for (int i = 0; i < 20; ++i) {
    const auto start = std::chrono::steady_clock::now();
    lfcam::Image photo = lfcam::refocus(small(), 0.63);
    fast = std::min(fast, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    benchmark::DoNotOptimize(photo.pixels().data());
  }
  const double perRun = secondsPerRun(state, [] { return lfcam::refocusReference(small(), 0.63); });
  state.counters["MP_per_s"] = 128.0 * 128.0 / 1e6 / perRun;
  state.counters["ratio"] = perRun / fast;  // reference time / fast time
}
BENCHMARK(BM_RefocusReference)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
