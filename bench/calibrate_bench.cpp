// Calibration of an Illum-size white image (7728 x 5368, GRBG mosaic, hexagonal grid of 14.29 px,
// rotated 0.15 degrees), synthesised analytically: a vignetted disc of light at each lattice centre,
// per-channel gains, noise. Goal: under 2 s on 2 cores. Reports the errors against the true
// grid, the peak memory (getrusage) and, measured in the same run, calibration with every
// microlens measured sub-pixel (Arg 0, the previous path) and, as the floor, one 3x3 median pass
// over the same image (the cheapest full pass calibration makes).
#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "core/parallel.hpp"
#include "lfcam/calibrate/calibrate.hpp"

namespace {

using namespace lfcam;

LensletGrid trueGrid() {
  LensletGrid grid;
  grid.packing = Packing::Hexagonal;
  grid.pitchX = 14.29;
  grid.pitchY = 14.29 * std::sqrt(3.0) / 2;
  grid.rotationRad = 0.15 * M_PI / 180;
  grid.origin = {9.37, 8.61};
  grid.columns = 540;
  grid.rows = 434;
  return grid;
}

// Brightness of a pixel: the nearest microlens's disc (radius 0.47 pitch, one-pixel soft edge),
// cos^4 vignetting across the sensor, GRBG gains, a hash for noise.
Image synthesiseWhite(const LensletGrid& grid, int width, int height) {
  Image image(width, height, 1);
  const double c = std::cos(grid.rotationRad), s = std::sin(grid.rotationRad);
  const double radius = 0.47 * grid.pitchX;
  parallelFor(0, std::size_t(height), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < width; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        const double dx = px - grid.origin[0], dy = py - grid.origin[1];
        const double b = (-s * dx + c * dy) / grid.pitchY;
        double nearest = INFINITY;
        for (int j = int(std::floor(b)); j <= int(std::floor(b)) + 1; ++j) {
          const double a = (c * dx + s * dy) / grid.pitchX - ((j & 1) ? 0.5 : 0.0);
          for (int i = int(std::floor(a)); i <= int(std::floor(a)) + 1; ++i) {
            const auto centre = grid.centre(i, j);
            nearest = std::min(nearest, std::hypot(px - centre[0], py - centre[1]));
          }
        }
        const double disc = std::clamp(radius + 0.5 - nearest, 0.0, 1.0);
        const double rx = (px - 0.5 * width) / width, ry = (py - 0.5 * height) / height;
        const double vignette = std::pow(1.0 / (1.0 + 0.8 * (rx * rx + ry * ry)), 2);
        const double gain = ((x & 1) == (y & 1)) ? 1.0 : ((y & 1) ? 0.55 : 0.7);  // GRBG: G, R / B, G
        std::uint32_t h = std::uint32_t(x) * 0x9E3779B1u ^ std::uint32_t(y) * 0x85EBCA77u;
        h ^= h >> 15;
        h *= 0x2C1B3C6Du;
        h ^= h >> 12;
        const double noise = (double(h & 0xFFFF) / 65535.0 - 0.5) * 0.02;
        image.at(x, y, 0) = float(0.06 + 0.8 * gain * vignette * disc + noise);
      }
  });
  return image;
}

const Image& illumWhite() {
  static const Image image = synthesiseWhite(trueGrid(), 7728, 5368);
  return image;
}

// state.range(0): CalibrationOptions::fitCentres (0: every microlens measured sub-pixel, the
// slower path that the subset is checked against).
void BM_CalibrateIllumWhite(benchmark::State& state) {
  const Image& white = illumWhite();
  CalibrationOptions options;
  options.colorFilter = ColorFilter::GRBG;
  options.fitCentres = int(state.range(0));
  LensletGrid grid;
  for (auto _ : state) {
    auto found = calibrateGrid(white, options, "illum");
    if (!found) {
      state.SkipWithError(found.error().message.c_str());
      return;
    }
    grid = *found;
  }
  const LensletGrid truth = trueGrid();
  // Centre error at the corners of the grid found: (0, 0) and (columns - 1, rows - 1) are
  // compared with the nearest true centre.
  auto nearestError = [&](std::array<double, 2> p) {
    const double c = std::cos(truth.rotationRad), s = std::sin(truth.rotationRad);
    const double dx = p[0] - truth.origin[0], dy = p[1] - truth.origin[1];
    const int j0 = int(std::round((-s * dx + c * dy) / truth.pitchY)),
              i0 = int(std::round((c * dx + s * dy) / truth.pitchX));
    double best = INFINITY;
    for (int j = j0 - 1; j <= j0 + 1; ++j)
      for (int i = i0 - 2; i <= i0 + 2; ++i) {
        const auto q = truth.centre(i, j);
        best = std::min(best, std::hypot(q[0] - p[0], q[1] - p[1]));
      }
    return best;
  };
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = double(usage.ru_maxrss) / 1024.0;
  state.counters["microlenses"] = grid.columns * grid.rows;
  state.counters["pitch_rel_error"] = std::abs(grid.pitchX / truth.pitchX - 1);
  state.counters["rotation_error_deg"] = std::abs(grid.rotationRad - truth.rotationRad) * 180 / M_PI;
  state.counters["corner_error_px"] =
      std::max(nearestError(grid.centre(0, 0)), nearestError(grid.centre(grid.columns - 1, grid.rows - 1)));
  state.counters["fit_rms_px"] = grid.fit.rmsResidualPx;
}
BENCHMARK(BM_CalibrateIllumWhite)
    ->Arg(CalibrationOptions{}.fitCentres)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

// The floor: one 3x3 median pass over the same image.
void BM_Median3x3IllumWhite(benchmark::State& state) {
  const Image& white = illumWhite();
  for (auto _ : state) {
    const Image median = median3x3(white);
    benchmark::DoNotOptimize(median.pixels().data());
  }
}
BENCHMARK(BM_Median3x3IllumWhite)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
