// lfcam bench INPUT [--repeat N] [--json]: the renderers side by side on one light field, in the
// manner of `zstd -b`. Loads the light field once, measures the machine's memory-copy bandwidth
// in the same run (bytes read plus bytes written per second, over buffers far larger than the
// caches), then times each renderer N times after a warm-up and prints the median seconds per
// photograph and its ratio to the floor: the light field's bytes as stored, read once at that
// bandwidth. Last, the fast method again on one thread, for the scaling over threads; with
// --stack N, a focal stack of N slices per method first (fast, quadrature, fourier), timed whole
// and reported per slice (fourier's 4D FFT included).
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "lfcam/focal_stack.hpp"
#include "lfcam/fourier_slice.hpp"
#include "lfcam/parallel.hpp"
#include "lfcam/refocus.hpp"
#include "lfcam/synthetic_camera.hpp"

namespace lfcam::cli {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Bytes read plus bytes written per second by a threaded memcpy of 256 MiB, best of `repeat`.
double copyBandwidth(int repeat) {
  const std::size_t bytes = std::size_t(256) << 20, slice = std::size_t(4) << 20;
  std::vector<char> source(bytes, 1), destination(bytes, 0);  // written first: no page faults timed
  double best = 1e30;
  for (int i = 0; i < std::max(2, repeat); ++i) {
    const auto start = std::chrono::steady_clock::now();
    parallelFor(0, bytes / slice, 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) std::memcpy(destination.data() + k * slice, source.data() + k * slice, slice);
    });
    best = std::min(best, secondsSince(start));
  }
  volatile char sink = destination[bytes / 2];
  (void)sink;
  return 2.0 * double(bytes) / best;
}

}  // namespace

void addBenchCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    int repeat = 5;
    bool json = false;
    bool noFourier = false;
    int stack = 0;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("bench", "time the renderers against the memory-copy floor");
  addInputOptions(*command, options->input);
  command->add_option("--repeat", options->repeat, "timed runs per method, after one warm-up")->check(CLI::Range(1, 1000));
  command->add_flag("--json", options->json, "a JSON list of {method, seconds_per_photo, floor_seconds, ratio_to_floor}");
  command->add_flag("--no-fourier", options->noFourier,
                    "skip the Fourier slice method (its spectrum needs about 8x the light field's memory)");
  command->add_option("--stack", options->stack, "also time a focal stack of N slices per method (0: none)")
      ->check(CLI::Range(0, 10000));
  command->callback([options, &job] {
    job = [options]() -> Status {
      auto loaded = loadInput(options->input);
      if (!loaded) return loaded.error();
      const LightField& lightField = *loaded;
      const double bandwidth = copyBandwidth(options->repeat);
      const double bytes = double(lightField.samples().size() + lightField.weights().size()) * sizeof(float);
      const double floorSeconds = bytes / bandwidth;

      // A fractional slope, so that every view is interpolated.
      const double slope = 0.63;
      struct Method {
        const char* name;
        std::function<Result<Image>()> render;
      };
      const std::vector<Method> methods = {
          {"fast", [&]() -> Result<Image> { return refocus(lightField, slope); }},
          {"fast-aperture",
           [&]() { return renderSyntheticPhoto(lightField, {.slope = slope, .aperture = Aperture::circle(0.25 * std::max(lightField.nu(), lightField.nv()))}); }},
          {"quadrature",
           [&]() {
             return renderSyntheticPhoto(lightField, {.slope = slope},
                                         {.method = RenderMethod::Quadrature, .supersampling = 2});
           }},
          {"observer", [&]() { return observe(lightField, {.u = 0.5, .v = 0.5}); }},
      };
      nlohmann::json results = nlohmann::json::array();
      if (!options->json)
        std::printf("%s: %.1f MB, memory copy %.2f GB/s (read + write), floor %.2f ms per photo\n",
                    options->input.path.c_str(), bytes / 1e6, bandwidth / 1e9, floorSeconds * 1e3);
      for (const Method& method : methods) {
        auto warm = method.render();
        if (!warm) return warm.error();
        std::vector<double> times;
        for (int i = 0; i < options->repeat; ++i) {
          const auto start = std::chrono::steady_clock::now();
          auto photo = method.render();
          times.push_back(secondsSince(start));
          if (!photo) return photo.error();
        }
        const double seconds = median(times);
        results.push_back({{"method", method.name},
                           {"seconds_per_photo", seconds},
                           {"floor_seconds", floorSeconds},
                           {"ratio_to_floor", seconds / floorSeconds}});
        if (!options->json)
          std::printf("%-14s %10.2f ms per photo  %6.2fx floor\n", method.name, seconds * 1e3, seconds / floorSeconds);
      }
      // Fourier slice: the 4D FFT once (reported apart), then per photo a slice and a 2D FFT.
      if (!options->noFourier) {
        const auto start = std::chrono::steady_clock::now();
        auto refocuser = FourierRefocuser::create(lightField);
        if (!refocuser) return refocuser.error();
        const double setup = secondsSince(start);
        { Image warm = refocuser->refocus(slope); }
        std::vector<double> times;
        for (int i = 0; i < options->repeat; ++i) {
          const auto begin = std::chrono::steady_clock::now();
          Image photo = refocuser->refocus(slope);
          times.push_back(secondsSince(begin));
        }
        const double seconds = median(times);
        results.push_back({{"method", "fourier"},
                           {"seconds_per_photo", seconds},
                           {"floor_seconds", floorSeconds},
                           {"ratio_to_floor", seconds / floorSeconds},
                           {"setup_seconds", setup},
                           {"spectrum_bytes", refocuser->spectrumBytes()}});
        if (!options->json) {
          std::printf("%-14s %10.2f ms per photo  %6.2fx floor  (4D FFT once: %.2f s, %.0f MB)\n", "fourier",
                      seconds * 1e3, seconds / floorSeconds, setup, refocuser->spectrumBytes() / 1e6);
          const double fast = results[0]["seconds_per_photo"];
          if (seconds < fast)
            std::printf("fourier beats fast from %.0f photos on\n", std::ceil(setup / (fast - seconds)));
          else
            std::printf("fourier is never faster than fast here\n");
        }
      }
      const auto report = [&](const std::string& name, double seconds, const char* unit) {
        results.push_back({{"method", name},
                           {"seconds_per_photo", seconds},
                           {"floor_seconds", floorSeconds},
                           {"ratio_to_floor", seconds / floorSeconds}});
        if (!options->json)
          std::printf("%-14s %10.2f ms per %-5s %6.2fx floor\n", name.c_str(), seconds * 1e3, unit, seconds / floorSeconds);
      };
      // Focal stacks over the scene's disparity range: the time of the whole stack per slice.
      if (options->stack > 0) {
        const std::vector<double> slopes = evenlySpaced(lightField.metadata.disparityMin.value_or(-2.0),
                                                        lightField.metadata.disparityMax.value_or(2.0), options->stack);
        const auto discard = [](int, double, Image&&) -> Status { return {}; };
        const auto timeStack = [&](const std::string& name, const RenderOptions& render) -> Status {
          const auto start = std::chrono::steady_clock::now();
          LFCAM_TRY(renderFocalStack(lightField, slopes, {}, render, discard));
          report(name, secondsSince(start) / double(slopes.size()), "slice");
          return {};
        };
        LFCAM_TRY(timeStack("stack-fast", {}));
        LFCAM_TRY(timeStack("stack-quadrature", {.method = RenderMethod::Quadrature, .supersampling = 2}));
        if (!options->noFourier) {
          const auto start = std::chrono::steady_clock::now();
          auto refocuser = FourierRefocuser::create(lightField);
          if (!refocuser) return refocuser.error();
          for (double sliceSlope : slopes) Image photo = refocuser->refocus(sliceSlope);
          report("stack-fourier", secondsSince(start) / double(slopes.size()), "slice");
        }
      }
      // Scaling: the fast method on one thread (last, since the limit stays for the process).
      {
        setThreadCount(1);
        { Image warm = refocus(lightField, slope); }
        std::vector<double> times;
        for (int i = 0; i < options->repeat; ++i) {
          const auto start = std::chrono::steady_clock::now();
          Image photo = refocus(lightField, slope);
          times.push_back(secondsSince(start));
        }
        const double oneThread = median(times);
        report("fast-1-thread", oneThread, "photo");
        if (!options->json)
          std::printf("fast: %.2fx faster on all threads than on one\n", oneThread / double(results[0]["seconds_per_photo"]));
      }
      if (options->json) std::printf("%s\n", results.dump(2).c_str());
      return {};
    };
  });
}

}  // namespace lfcam::cli
