// lfcam bench INPUT [--repeat N] [--json]: the renderers side by side on one light field, in the
// manner of `zstd -b`. Loads the light field once, then times each renderer N times after a
// warm-up, each time just after measuring the machine's memory-copy bandwidth (bytes read plus
// bytes written per second, over buffers far larger than the caches), and prints the median
// seconds per photograph, the median floor (the light field's bytes as stored, read once at that
// bandwidth) and the median ratio of a photo's time to the floor measured just before it. Last, the fast method on one
// thread and on all, alternately, for the scaling over threads; with
// --stack N, a focal stack of N slices per method first (fast, quadrature, fourier), timed whole
// and reported per slice (fourier's 4D FFT included).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "core/memory_floor.hpp"
#include "core/parallel.hpp"
#include "lfcam/render/focal_stack.hpp"
#include "lfcam/render/fourier_slice.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/render/synthetic_camera.hpp"

namespace lfcam::cli {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Timed runs, each just after a measurement of the floor: medians of the times, of the floors,
// and of the ratio of each run to its own floor (the figure that the machine's changes of speed
// disturb least: the two of a pair are some 20 ms apart).
struct Timing {
  double seconds = 0, floorSeconds = 0, ratio = 0;
};

struct TimedRuns {
  std::vector<double> times, floors;
  void add(double seconds, double floorSeconds) { times.push_back(seconds), floors.push_back(floorSeconds); }
  Timing summary() const {
    std::vector<double> ratios;
    for (std::size_t i = 0; i < times.size(); ++i) ratios.push_back(times[i] / floors[i]);
    return {medianOf(times), medianOf(floors), medianOf(ratios)};
  }
};

// `repeat` timed runs of `render` after one warm-up.
Result<Timing> timeAgainstFloor(int repeat, MemoryFloor& floor, const std::function<Status()>& render) {
  LFCAM_TRY(render());
  TimedRuns runs;
  for (int i = 0; i < repeat; ++i) {
    const double floorSeconds = floor.measure();
    const auto start = std::chrono::steady_clock::now();
    LFCAM_TRY(render());
    runs.add(secondsSince(start), floorSeconds);
  }
  return runs.summary();
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
  command->add_option("--repeat", options->repeat, "timed runs per method, after one warm-up")
      ->check(CLI::Range(1, 1000));
  command->add_flag("--json", options->json,
                    "a JSON list of {method, seconds_per_photo, floor_seconds, ratio_to_floor}");
  command->add_flag("--no-fourier", options->noFourier,
                    "skip the Fourier slice method (its spectrum needs about 8x the light field's memory)");
  command->add_option("--stack", options->stack, "also time a focal stack of N slices per method (0: none)")
      ->check(CLI::Range(0, 10000));
  command->callback([options, &job] {
    job = [options]() -> Status {
      LFCAM_ASSIGN_OR_RETURN(auto loaded, loadInput(options->input));
      const LightField& lightField = loaded;
      const double bytes = double(lightField.samples().size() + lightField.weights().size()) * sizeof(float);
      MemoryFloor floor(bytes);
      for (int i = 0; i < 3; ++i) floor.measure();  // warm-up, and the bandwidth of the header line

      // A fractional slope, so that every view is interpolated.
      const double slope = 0.63;
      struct Method {
        const char* name;
        std::function<Result<Image>()> render;
      };
      const std::vector<Method> methods = {
          {"fast", [&]() -> Result<Image> { return refocus(lightField, slope); }},
          {"fast-aperture",
           [&]() {
             return renderSyntheticPhoto(
                 lightField,
                 {.slope = slope, .aperture = Aperture::circle(0.25 * std::max(lightField.nu(), lightField.nv()))});
           }},
          {"quadrature",
           [&]() {
             return renderSyntheticPhoto(lightField, {.slope = slope},
                                         {.method = RenderMethod::Quadrature, .supersampling = 2});
           }},
          {"observer", [&]() { return observe(lightField, {.u = 0.5, .v = 0.5}); }},
      };
      nlohmann::json results = nlohmann::json::array();
      const auto report = [&](const std::string& name, const Timing& timing, const char* unit) -> nlohmann::json& {
        results.push_back({{"method", name},
                           {"seconds_per_photo", timing.seconds},
                           {"floor_seconds", timing.floorSeconds},
                           {"ratio_to_floor", timing.ratio}});
        if (!options->json)
          std::printf("%-16s %9.2f ms per %-5s  floor %7.2f ms  %6.2fx floor\n", name.c_str(), timing.seconds * 1e3,
                      unit, timing.floorSeconds * 1e3, timing.ratio);
        return results.back();
      };
      if (!options->json)
        std::printf("%s: %.1f MB, memory copy %.2f GB/s (read + write, median), floor measured before each photo\n",
                    options->input.path.c_str(), bytes / 1e6, floor.medianBandwidth() / 1e9);
      for (const Method& method : methods) {
        auto render = [&]() -> Status {
          LFCAM_TRY(method.render());
          return {};
        };
        LFCAM_ASSIGN_OR_RETURN(const auto timing, timeAgainstFloor(options->repeat, floor, render));
        report(method.name, timing, "photo");
      }
      // Fourier slice: the 4D FFT once (reported apart), then per photo a slice and a 2D FFT.
      if (!options->noFourier) {
        const auto start = std::chrono::steady_clock::now();
        LFCAM_ASSIGN_OR_RETURN(auto refocuser, FourierRefocuser::create(lightField));
        const double setup = secondsSince(start);
        auto render = [&]() -> Status {
          Image photo = refocuser.refocus(slope);
          return {};
        };
        LFCAM_ASSIGN_OR_RETURN(const auto timing, timeAgainstFloor(options->repeat, floor, render));
        nlohmann::json& entry = report("fourier", timing, "photo");
        entry["setup_seconds"] = setup;
        entry["spectrum_bytes"] = refocuser.spectrumBytes();
        if (!options->json) {
          std::printf("%-16s 4D FFT once: %.2f s, %.0f MB\n", "", setup, refocuser.spectrumBytes() / 1e6);
          const double fast = results[0]["seconds_per_photo"];
          if (timing.seconds < fast)
            std::printf("fourier beats fast from %.0f photos on\n", std::ceil(setup / (fast - timing.seconds)));
          else
            std::printf("fourier is never faster than fast here\n");
        }
      }
      // Focal stacks over the scene's disparity range: the time of the whole stack per slice.
      if (options->stack > 0) {
        const std::vector<double> slopes = evenlySpaced(lightField.metadata.disparityMin.value_or(-2.0),
                                                        lightField.metadata.disparityMax.value_or(2.0), options->stack);
        const auto discard = [](int, double, Image&&) -> Status { return {}; };
        const auto timeStack = [&](const std::string& name, const std::function<Status()>& stack) -> Status {
          const double floorSeconds = floor.measure();
          const auto start = std::chrono::steady_clock::now();
          LFCAM_TRY(stack());
          TimedRuns run;
          run.add(secondsSince(start) / double(slopes.size()), floorSeconds);
          report(name, run.summary(), "slice");
          return {};
        };
        LFCAM_TRY(timeStack("stack-fast", [&] { return renderFocalStack(lightField, slopes, {}, {}, discard); }));
        LFCAM_TRY(timeStack("stack-quadrature", [&] {
          return renderFocalStack(lightField, slopes, {}, {.method = RenderMethod::Quadrature, .supersampling = 2},
                                  discard);
        }));
        if (!options->noFourier)
          LFCAM_TRY(timeStack("stack-fourier", [&]() -> Status {
            LFCAM_ASSIGN_OR_RETURN(auto refocuser, FourierRefocuser::create(lightField));
            for (double sliceSlope : slopes) Image photo = refocuser.refocus(sliceSlope);
            return {};
          }));
      }
      // Scaling: the fast method on one thread and on all, alternately, each against its floors.
      {
        TimedRuns one, all;
        const auto timeOn = [&](int threads, TimedRuns& runs, double floorSeconds) {
          setThreadCount(threads);
          const auto start = std::chrono::steady_clock::now();
          Image photo = refocus(lightField, slope);
          runs.add(secondsSince(start), floorSeconds);
          setThreadCount(0);
        };
        for (int i = 0; i < options->repeat; ++i) {
          const double floorSeconds = floor.measure();  // on all threads: the machine's floor
          timeOn(1, one, floorSeconds);
          timeOn(0, all, floorSeconds);
        }
        report("fast-1-thread", one.summary(), "photo");
        if (!options->json)
          std::printf("fast: %.2fx faster on all threads than on one (the two alternately, median)\n",
                      one.summary().seconds / all.summary().seconds);
      }
      if (options->json) std::printf("%s\n", results.dump(2).c_str());
      return {};
    };
  });
}

}  // namespace lfcam::cli
