// Refocus speed, as ratios to floors measured in the same run (style.md, point 8):
//   BM_MemoryCopy         a large memcpy of the light field's size, threaded like refocus: the
//                         bandwidth that sets the floor.
//   BM_MemoryRead         the antinous light field's samples read once by a threaded reduction
//                         (XOR of their bits, which the compiler vectorises), alternating with the
//                         copy: ratio = read time / floor, what reading alone reaches here.
//   BM_Refocus            refocus of the HCI "antinous" light field (9x9 views, 512x512 RGB), or
//                         a layered-planes field of the same size when the data is absent.
//                         Counters: output megapixels per second, floor_ms = the light field's
//                         bytes read once at the memcpy bandwidth, ratio = time / floor.
//   BM_RefocusIllum       the same for a light field of a Lytro Illum's size (15x15 views of
//                         625x434 RGB, 732 MB), synthesised as layered planes, with its own floor.
//   BM_RefocusThreads     refocus of the antinous field on 1 and on 2 threads: the scaling.
//   BM_RefocusPages       refocus of the antinous field on huge pages (as LightField allocates it)
//                         and of a copy on 4 KiB pages (ratio = time / huge-page time, alternately).
//   BM_RefocusReference   the float64 oracle against the fast kernel on a smaller field
//                         (ratio = reference time / fast time).
//
// Run: build-*/bench/refocus_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>
#include <sys/prctl.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "lfcam/huge_page_allocator.hpp"
#include "lfcam/layered_planes.hpp"
#include "lfcam/light_field_io.hpp"
#include "lfcam/parallel.hpp"
#include "lfcam/refocus.hpp"

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

// Copies `bytes` in slices over parallelFor's threads, as refocus spreads its reads.
void parallelCopy(char* destination, const char* source, std::size_t bytes) {
  const std::size_t slice = 4 << 20;
  lfcam::parallelFor(0, (bytes + slice - 1) / slice, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t offset = i * slice;
      std::memcpy(destination + offset, source + offset, std::min(slice, bytes - offset));
    }
  });
}

// Seconds of one copy of `bytes`, best of `copies` (the floor should be the machine's best).
double bestCopySeconds(std::size_t bytes, int copies) {
  // Both buffers written first, so page faults stay out of the timing; on huge pages, like the
  // light field's samples.
  std::vector<char, lfcam::HugePageAllocator<char>> source(bytes, 1), destination(bytes, 0);
  double best = 1e30;
  for (int i = 0; i < copies; ++i) {
    const auto start = std::chrono::steady_clock::now();
    parallelCopy(destination.data(), source.data(), bytes);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    benchmark::DoNotOptimize(destination.data());
    benchmark::ClobberMemory();
  }
  return best;
}

// The floor: the light field's bytes read once at the bandwidth of a large memcpy, measured once
// per run. (A memcpy also writes what it reads, so this floor is generous by up to 2x; refocus
// writes only the small photograph.)
double floorSeconds(const LightField& lightField) {
  static std::map<const LightField*, double> seconds;  // per light field, measured once
  auto found = seconds.find(&lightField);
  if (found == seconds.end()) found = seconds.emplace(&lightField, bestCopySeconds(bytesOf(lightField), 5)).first;
  return found->second;
}

void BM_MemoryCopy(benchmark::State& state) {
  const std::size_t bytes = bytesOf(antinous());
  std::vector<char> source(bytes, 1), destination(bytes, 0);
  for (auto _ : state) {
    parallelCopy(destination.data(), source.data(), bytes);
    benchmark::DoNotOptimize(destination.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(std::int64_t(bytes) * state.iterations());
  state.counters["MB"] = double(bytes) / 1e6;
  state.counters["floor_ms"] = floorSeconds(antinous()) * 1e3;
}
BENCHMARK(BM_MemoryCopy)->Unit(benchmark::kMillisecond)->UseRealTime();

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
  const LightField& lightField = antinous();
  const std::size_t bytes = bytesOf(lightField);
  std::vector<char, lfcam::HugePageAllocator<char>> source(bytes, 1), destination(bytes, 0);
  double readSeconds = 0, copySeconds = 0;
  for (auto _ : state) {
    auto start = std::chrono::steady_clock::now();
    parallelCopy(destination.data(), source.data(), bytes);
    copySeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::ClobberMemory();
    start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(readAll(lightField));
    readSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  // The copy moves the bytes twice (read and write): the floor is half its time.
  state.counters["ratio"] = readSeconds / (0.5 * copySeconds);
}
BENCHMARK(BM_MemoryRead)->Unit(benchmark::kMillisecond)->UseRealTime();

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

void BM_Refocus(benchmark::State& state) {
  const LightField& lightField = antinous();
  const double slope = double(state.range(0)) / 100.0;
  const double perRun = secondsPerRun(state, [&] { return lfcam::refocus(lightField, slope); });
  const double floor = floorSeconds(lightField);
  state.counters["MP_per_s"] = double(lightField.ns()) * lightField.nt() / 1e6 / perRun;
  state.counters["floor_ms"] = floor * 1e3;
  state.counters["ratio"] = perRun / floor;
  state.SetLabel(lightField.metadata.source.empty() ? "hci-antinous" : lightField.metadata.source);
}
// Slopes in hundredths: 0 (whole-pixel shifts), fractional ones, and one that moves the outer
// views 6 pixels.
BENCHMARK(BM_Refocus)->Arg(0)->Arg(-37)->Arg(63)->Arg(150)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RefocusIllum(benchmark::State& state) {
  const LightField& lightField = illum();
  const double perRun = secondsPerRun(state, [&] { return lfcam::refocus(lightField, 0.63); });
  const double floor = floorSeconds(lightField);
  state.counters["MP_per_s"] = double(lightField.ns()) * lightField.nt() / 1e6 / perRun;
  state.counters["floor_ms"] = floor * 1e3;
  state.counters["ratio"] = perRun / floor;
  state.SetLabel("15x15x625x434 RGB");
}
BENCHMARK(BM_RefocusIllum)->Unit(benchmark::kMillisecond)->UseRealTime();

// Threads as the argument; the thread limit is lifted again afterwards.
void BM_RefocusThreads(benchmark::State& state) {
  const LightField& lightField = antinous();
  const double floor = floorSeconds(lightField);
  lfcam::setThreadCount(int(state.range(0)));
  const double perRun = secondsPerRun(state, [&] { return lfcam::refocus(lightField, 0.63); });
  lfcam::setThreadCount(0);
  state.counters["floor_ms"] = floor * 1e3;
  state.counters["ratio"] = perRun / floor;
}
BENCHMARK(BM_RefocusThreads)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

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
