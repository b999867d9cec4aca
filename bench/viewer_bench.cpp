// Viewer latency (issue 8: click-to-photo under 100 ms for an hci-antinous-size light field on 2
// cores), measured over HTTP on loopback from sending the request to the last byte of the JPEG,
// as ratios to a floor measured in the same run:
//   BM_Refocus        one refocus of the light field (the floor: the least a new photo costs).
//   BM_ClickToPhoto   GET /api/image?focus-at=X,Y: pick the sharpest slope at a clicked point, render
//                     the full-aperture photograph, encode JPEG, send. Cache off, so every click
//                     renders. Counters: median_ms, p99_ms, ratio = median / refocus.
//   BM_SliderToPhoto  GET /api/image?slope=D&f-number=2 (a focus-slider step through a smaller aperture).
//   BM_FocusSearch, BM_EncodeJpeg   the parts of a click besides the render (ratio = time / refocus).
// The light field: ../shared/data/hci-antinous (9x9 views, 512x512 RGB), else layered planes of
// the same size (said on stderr).
//
// Run: build-*/bench/viewer_bench --benchmark_min_time=3s   (lfcam --threads is 0: all cores)
#include <benchmark/benchmark.h>
#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>

#include "lfcam/io/light_field_io.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "lfcam/viewer/viewer.hpp"
#include "lfcam/viewer/viewer_server.hpp"
#include "viewer/image_encode.hpp"

namespace {

using Clock = std::chrono::steady_clock;

lfcam::LightField loadLightField() {
  const char* folder = LFCAM_SHARED_DATA_DIR "/hci-antinous";
  auto read = lfcam::readLightField(folder);
  if (read) return std::move(read).value();
  std::fprintf(stderr,
               "viewer_bench: cannot read %s (%s);\n  using layered planes of the same size (9x9 views, 512x512 RGB)\n",
               folder, read.error().message.c_str());
  return std::move(lfcam::renderLayeredPlanes(lfcam::defaultLayeredPlanesScene(9, 512)).lightField);
}

// The session and its server, started once for every benchmark.
struct Viewer {
  lfcam::ViewerSession session{loadLightField(), lfcam::ViewerLimits{.cacheBytes = 0}};
  lfcam::ViewerServer server{session};
  std::thread thread;
  Viewer() {
    if (auto bound = server.bind({.host = "127.0.0.1", .port = 0}); !bound) {
      std::fprintf(stderr, "viewer_bench: %s\n", bound.error().message.c_str());
      std::exit(1);
    }
    thread = std::thread([this] { (void)server.run(); });
  }
  ~Viewer() {
    server.stop();
    thread.join();
  }
};

Viewer& viewer() {
  static Viewer instance;
  return instance;
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, std::size_t(p * (values.size() - 1) + 0.5))];
}

double refocusMs = 0;

void BM_Refocus(benchmark::State& state) {
  const lfcam::LightField& lf = viewer().session.lightField();
  std::vector<double> times;
  for (auto _ : state) {
    const auto start = Clock::now();
    benchmark::DoNotOptimize(lfcam::refocus(lf, 0.3));
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  refocusMs = percentile(times, 0.5);
  state.counters["median_ms"] = refocusMs;
}

// The parts of a click besides the render, for the breakdown: the focus search, the JPEG.
void timed(benchmark::State& state, const std::function<void(int)>& work) {
  std::vector<double> times;
  int i = 0;
  for (auto _ : state) {
    const auto start = Clock::now();
    work(i++);
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  state.counters["median_ms"] = percentile(times, 0.5);
  if (refocusMs > 0) state.counters["ratio"] = percentile(times, 0.5) / refocusMs;
}

void BM_FocusSearch(benchmark::State& state) {
  const auto& s = viewer().session;
  timed(state, [&](int i) { benchmark::DoNotOptimize(s.focusAt(16 + (i * 37) % 480, 16 + (i * 53) % 480)); });
}

void BM_EncodeJpeg(benchmark::State& state) {
  const lfcam::Image photo = lfcam::refocus(viewer().session.lightField(), 0.3);
  timed(state, [&](int) { benchmark::DoNotOptimize(lfcam::encodeImage(photo, {.jpegQuality = 80})); });
}

// Latency of GET `path(i)` for the i-th request, over one kept-alive connection.
void measure(benchmark::State& state, const std::function<std::string(int)>& path) {
  httplib::Client client("127.0.0.1", viewer().server.port());
  client.set_keep_alive(true);
  std::vector<double> times;
  int i = 0, failures = 0;
  for (auto _ : state) {
    const auto start = Clock::now();
    auto answer = client.Get(path(i++));
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    if (!answer || answer->status != 200 || answer->body.size() < 100) ++failures;
  }
  if (failures) state.SkipWithError("some requests failed");
  const double median = percentile(times, 0.5);
  state.counters["median_ms"] = median;
  state.counters["p99_ms"] = percentile(times, 0.99);
  state.counters["max_ms"] = percentile(times, 1.0);
  if (refocusMs > 0) state.counters["ratio"] = median / refocusMs;
}

void BM_ClickToPhoto(benchmark::State& state) {
  const lfcam::LightField& lf = viewer().session.lightField();
  measure(state, [&](int i) {
    // Points spread over the image by a low-discrepancy walk, away from the border.
    const int x = 16 + int((i * 0.6180339887 - int(i * 0.6180339887)) * (lf.ns() - 32));
    const int y = 16 + int((i * 0.7548776662 - int(i * 0.7548776662)) * (lf.nt() - 32));
    return "/api/image?focus-at=" + std::to_string(x) + "," + std::to_string(y);
  });
}

void BM_SliderToPhoto(benchmark::State& state) {
  measure(state, [&](int i) {
    const auto& s = viewer().session;
    const double slope = s.slopeMin() + (s.slopeMax() - s.slopeMin()) * ((i * 37) % 101) / 100.0;
    return "/api/image?f-number=2&slope=" + std::to_string(slope);
  });
}

BENCHMARK(BM_Refocus)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(30);
BENCHMARK(BM_FocusSearch)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(30);
BENCHMARK(BM_EncodeJpeg)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(30);
BENCHMARK(BM_ClickToPhoto)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(200);
BENCHMARK(BM_SliderToPhoto)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(200);

}  // namespace

BENCHMARK_MAIN();
