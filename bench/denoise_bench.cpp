// lfcam denoise on simulator captures with the sensor's noise model (issue 20, item 4). Each scene
// is traced once through the people tests' camera (9x9 views of 80x80), each frame the sensor model
// with its own noise, decoded on the true grid (the experiments' capture chain), against the
// noise-free frame of the same trace. The filter is linear, so the noise that passes is the
// filtered noisy capture minus the filtered noise-free one, and what it does to the scene is the
// filtered noise-free capture against the unfiltered one.
//
// Sharpness at the in-focus depth: the chart of vertical sine gratings (tests/sine_chart.hpp) at
// a slope inside the passband; the modulation of each grating below the views' Nyquist frequency
// (0.15-0.45 cycles per pixel) in the centre view and in the photo refocused at the chart's slope,
// noise-free, after the filter over before (1: the filter keeps the in-focus detail), and MTF50.
// The gradient energy of everything is no measure of it: a decoded view's finest detail is mostly
// what the views do not share (aliasing, the decoding's pixel-scale pattern), which no surface
// puts on a slope plane and which a refocused photo averages away too.
//
// Development (--development): the chart at slopes -0.75, -0.25, 0.25 and 0.5 through the passband
// -1:0.75 at several bandwidths (--bandwidth B, repeatable): where the default bandwidth was chosen;
// with each view's modulation of the finest grating, how sharp the views are. --ideal: the same on
// the simulator's ideal light field with white noise instead of the sensor capture (every view
// equally sharp), to tell what the filter loses from what the capture's views do not share.
// Report (default): the scene never used for tuning, `people` (its cards' disparities, passband
// 0.25 wider on each side): SNR (mean over rms error against the noise-free capture) of the centre
// view and of the photo refocused at each card's disparity, before and after, and the noise alone;
// with the chart placed at each card's disparity for sharpness. Exposure 0.1 (--exposure E): a ten
// times shorter exposure than the simulator's default. Then the filter's time on one capture.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/experiment_support.hpp"
#include "lfcam/analysis/analysis.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/render/denoise.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "people_camera.hpp"
#include "people_cards.hpp"
#include "sine_chart.hpp"

namespace lfcam {
namespace {

// A scene's noise-free and noisy captures, and both filtered.
struct Captures {
  LightField clean, noisy, cleanFiltered, noisyFiltered;
};

// Instead of the sensor capture, the simulator's ideal light field (each sample the mean radiance
// over its pixel's footprint, every view equally sharp) with white noise of the sensor capture's
// rms at exposure 0.1: what the filter does when the views share all their detail.
bool idealViews = false;
constexpr float kIdealNoise = 0.017f;

Captures capture(const Scene& scene, const CameraModel& camera) {
  if (idealViews) {
    auto ideal = idealLightFieldBoxFiltered(scene, camera, 4);
    if (!ideal) throw std::runtime_error(ideal.error().message);
    // Its central 9 x 9 views (it has as many as a microlens image is pixels across: 12 without
    // --matched), as many as the decoded capture's.
    LightFieldShape shape = ideal->shape();
    const int first = (shape.nu - 9) / 2;
    shape.nu = shape.nv = 9;
    LightField clean(shape);
    clean.metadata = ideal->metadata;
    clean.enableWeight();
    for (int v = 0; v < 9; ++v)
      for (int u = 0; u < 9; ++u) {
        for (int c = 0; c < shape.channels; ++c)
          std::copy_n(ideal->plane(u + first, v + first, c), shape.viewPixels(), clean.plane(u, v, c));
        std::copy_n(ideal->weightPlane(u + first, v + first), shape.viewPixels(), clean.weightPlane(u, v));
      }
    LightField noisy = clean.copy();
    std::mt19937 generator(7);
    std::normal_distribution<float> normal(0.0f, kIdealNoise);
    for (float& sample : noisy.samples()) sample += normal(generator);
    return {std::move(clean), std::move(noisy), {}, {}};
  }
  auto traced = experiments::traceCapture(scene, camera, 64);
  if (!traced) throw std::runtime_error(traced.error().message);
  auto clean = experiments::captureLightField(*traced, false, 0);
  auto noisy = experiments::captureLightField(*traced, true, 7);
  if (!clean || !noisy) throw std::runtime_error("capture failed");
  return {std::move(*clean), std::move(*noisy), {}, {}};
}

void filter(Captures& captures, const DenoiseOptions& options) {
  auto cleanFiltered = denoise(captures.clean, options);
  auto noisyFiltered = denoise(captures.noisy, options);
  if (!cleanFiltered || !noisyFiltered) throw std::runtime_error("denoise failed");
  captures.cleanFiltered = std::move(*cleanFiltered);
  captures.noisyFiltered = std::move(*noisyFiltered);
}

Image centreView(const LightField& lightField) {
  return lightField.subApertureImage((lightField.nu() - 1) / 2, (lightField.nv() - 1) / 2);
}

// One photograph of the captures (the centre view, or a refocused photo), before and after.
struct Photos {
  Image clean, noisy, cleanFiltered, noisyFiltered;
};

template <class Make>
Photos photosOf(const Captures& captures, Make make) {
  return {make(captures.clean), make(captures.noisy), make(captures.cleanFiltered), make(captures.noisyFiltered)};
}

// Noise rms before and after (filtered noisy minus filtered noise-free: the filter is linear), and
// SNR against the unfiltered noise-free photo before and after (the filter's change to the scene
// counts as error).
struct NoiseFigures {
  double noiseBefore = 0, noiseAfter = 0, snrBefore = 0, snrAfter = 0;
};

NoiseFigures noiseOf(const Photos& photos, const Image* mask) {
  return {signalToNoise(photos.noisy, photos.clean, mask)->noise,
          signalToNoise(photos.noisyFiltered, photos.cleanFiltered, mask)->noise,
          signalToNoise(photos.noisy, photos.clean, mask)->snr,
          signalToNoise(photos.noisyFiltered, photos.clean, mask)->snr};
}

// The central three quarters of the chart's field (the modulation fit's own region).
Image chartMask(const Image& photo) {
  Image mask(photo.width(), photo.height(), 1);
  for (int y = photo.height() / 8; y < photo.height() - photo.height() / 8; ++y)
    for (int x = photo.width() / 8; x < photo.width() - photo.width() / 8; ++x) mask.at(x, y, 0) = 1;
  return mask;
}

// Sharpness on the chart, noise-free: the smallest ratio after / before of the gratings'
// modulation below the views' Nyquist frequency, and MTF50 before and after.
struct Sharpness {
  double worstKept = 0, mtf50Before = 0, mtf50After = 0;
};

Sharpness sharpnessOf(const Photos& photos) {
  const std::vector<double> before = test::modulationPerBand(photos.clean, 1);
  const std::vector<double> after = test::modulationPerBand(photos.cleanFiltered, 1);
  Sharpness sharpness{INFINITY, test::mtf50(before, 1), test::mtf50(after, 1)};
  for (std::size_t band = 0; band < before.size(); ++band)
    if (test::kChartFrequencies[band] < 0.5)
      sharpness.worstKept = std::min(sharpness.worstKept, after[band] / before[band]);
  return sharpness;
}

void printChartHeader() {
  std::printf(
      "| bandwidth | chart slope | centre: modulation kept (worst grating) | MTF50 before | after | noise rms before | "
      "after | ratio | refocused: modulation kept | MTF50 before | after | noise rms before | after | ratio |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

void chartRow(const Captures& captures, double slope, const DenoiseOptions& options);
bool printViews = false;

// Rows: the chart at `slope` through each passband of `passbands`.
void chartRows(const CameraModel& camera, const Optics& optics, double slope,
               const std::vector<DenoiseOptions>& passbands) {
  Captures captures = capture(test::sineChartScene(camera, *distanceFromDisparity(optics, slope)), camera);
  if (printViews) {
    // How sharp each view is: the finest grating below Nyquist (band 3, 0.45 cycles per pixel).
    std::printf("| %+.2f | views of the centre row, modulation at 0.45 cycles/px:", slope);
    const int v = (captures.clean.nv() - 1) / 2;
    for (int u = 0; u < captures.clean.nu(); ++u)
      std::printf(" %.2f", test::modulationPerBand(captures.clean.subApertureImage(u, v), 1)[3]);
    std::printf(" |\n");
  }
  for (const DenoiseOptions& options : passbands) {
    filter(captures, options);
    chartRow(captures, slope, options);
  }
}

void chartRow(const Captures& captures, double slope, const DenoiseOptions& options) {
  std::printf("| %.3f | %+.2f |", options.bandwidth, slope);
  auto columns = [&](const Photos& photos) {
    const Image mask = chartMask(photos.clean);
    const Sharpness sharpness = sharpnessOf(photos);
    const NoiseFigures noise = noiseOf(photos, &mask);
    std::printf(" %.3f | %.3f | %.3f | %.4f | %.4f | %.2fx |", sharpness.worstKept, sharpness.mtf50Before,
                sharpness.mtf50After, noise.noiseBefore, noise.noiseAfter, noise.noiseBefore / noise.noiseAfter);
  };
  columns(photosOf(captures, centreView));
  columns(photosOf(captures, [&](const LightField& lightField) { return refocus(lightField, slope); }));
  std::printf("\n");
}

// The people tests' camera (9x9 views of 80x80): its main lens at image-side f/2.9 makes microlens
// images 12 pixels across on a 9-pixel pitch, the outer pixels of each cell mixing light from the
// next microlens. --matched stops the main lens to image-side f/4, the microlenses' f-number, so
// that the microlens images tile the sensor (the paper's section 3.1).
bool matched = false;

CameraModel benchCamera(double exposure) {
  CameraModel camera = test::peopleCamera();
  camera.sensor.exposure = exposure;
  if (matched) camera.mainLens.setImageSideFNumber(4);
  return camera;
}

// The optics of the people camera (from a capture's metadata).
Optics opticsOf(const CameraModel& camera) {
  auto ideal = idealLightField(*builtinScene("white", camera), camera);
  if (!ideal || !ideal->metadata.optics) throw std::runtime_error("no optics");
  return *ideal->metadata.optics;
}

void development(double exposure, const std::vector<double>& bandwidths) {
  const CameraModel camera = benchCamera(exposure);
  const Optics optics = opticsOf(camera);
  if (idealViews)
    std::printf("\ndevelopment: the sine chart, ideal 9 x 9 views with white noise of rms %.3f, passband -1.00:0.75\n",
                kIdealNoise);
  else
    std::printf("\ndevelopment: the sine chart, %s camera, exposure %.2f, passband -1.00:0.75\n",
                matched ? "matched" : "overlapping", exposure);
  printViews = true;
  printChartHeader();
  std::vector<DenoiseOptions> passbands;
  for (double bandwidth : bandwidths) passbands.push_back({.slopeMin = -1.0, .slopeMax = 0.75, .bandwidth = bandwidth});
  for (double slope : {-0.75, -0.25, 0.25, 0.5}) chartRows(camera, optics, slope, passbands);
}

// 1 on the card's interior pixels (indexed in the `cardWidth` columns of the ideal depth; the
// decoded capture's (s, t) start at the same microlens and may stop one short).
Image maskOf(const test::Card& card, int cardWidth, int width, int height) {
  Image mask(width, height, 1);
  for (std::size_t i : card.interior) {
    const int x = int(i % std::size_t(cardWidth)), y = int(i / std::size_t(cardWidth));
    if (x < width && y < height) mask.at(x, y, 0) = 1.0f;
  }
  return mask;
}

void report(double exposure, double bandwidth) {
  const CameraModel camera = benchCamera(exposure);
  const Scene scene = *builtinScene("people", camera);
  const Optics optics = opticsOf(camera);
  const Image depth = *idealDepth(scene, camera);
  const std::vector<test::Card> cards = test::sceneCards(scene, depth, optics);
  DenoiseOptions options{.slopeMin = INFINITY, .slopeMax = -INFINITY, .bandwidth = bandwidth};
  for (const test::Card& card : cards)
    options.slopeMin = std::min(options.slopeMin, card.disparity - 0.25),
    options.slopeMax = std::max(options.slopeMax, card.disparity + 0.25);
  Captures captures = capture(scene, camera);
  filter(captures, options);
  std::printf(
      "\nreport: people, %s camera, exposure %.2f (%d x %d views of %d x %d), passband %.2f:%.2f, bandwidth %.3f\n",
      matched ? "matched" : "overlapping", exposure, captures.clean.nu(), captures.clean.nv(), captures.clean.ns(),
      captures.clean.nt(), options.slopeMin, options.slopeMax, options.bandwidth);
  std::printf(
      "| card | disparity | centre view SNR before | after | noise rms before | after | ratio | refocused SNR before | "
      "after | noise rms before | after | ratio |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const Photos centre = photosOf(captures, centreView);
  for (const test::Card& card : cards) {
    const Image mask = maskOf(card, depth.width(), captures.clean.ns(), captures.clean.nt());
    const Photos photo =
        photosOf(captures, [&](const LightField& lightField) { return refocus(lightField, card.disparity); });
    std::printf("| %s | %+.2f |", card.name.c_str(), card.disparity);
    for (const Photos* photos : {&centre, &photo}) {
      const NoiseFigures noise = noiseOf(*photos, &mask);
      std::printf(" %.1f | %.1f | %.4f | %.4f | %.2fx |", noise.snrBefore, noise.snrAfter, noise.noiseBefore,
                  noise.noiseAfter, noise.noiseBefore / noise.noiseAfter);
    }
    std::printf("\n");
  }
  std::printf("\nsharpness: the sine chart at each card's disparity, the same passband\n");
  printChartHeader();
  for (const test::Card& card : cards) chartRows(camera, optics, card.disparity, {options});
}

// The filter's time on a noisy capture.
void BM_Denoise(benchmark::State& state) {
  const CameraModel camera = test::peopleCamera();
  auto traced = experiments::traceCapture(*builtinScene("people", camera), camera, 4);
  auto noisy = experiments::captureLightField(*traced, true, 7);
  const DenoiseOptions options{.slopeMin = -1.25, .slopeMax = 0.75};
  for (auto _ : state) benchmark::DoNotOptimize(denoise(*noisy, options));
}
BENCHMARK(BM_Denoise)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace
}  // namespace lfcam

int main(int argc, char** argv) {
  double exposure = 0.1;
  bool development = false;
  std::vector<double> bandwidths;
  std::vector<char*> rest{argv[0]};
  std::printf("command:");  // the tables below come from it
  for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
  std::printf("\n");
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--development") == 0)
      development = true;
    else if (std::strcmp(argv[i], "--matched") == 0)
      lfcam::matched = true;
    else if (std::strcmp(argv[i], "--ideal") == 0)
      lfcam::idealViews = true;
    else if (std::strcmp(argv[i], "--exposure") == 0 && i + 1 < argc)
      exposure = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--bandwidth") == 0 && i + 1 < argc)
      bandwidths.push_back(std::atof(argv[++i]));
    else
      rest.push_back(argv[i]);
  }
  if (bandwidths.empty()) bandwidths.push_back(lfcam::DenoiseOptions{}.bandwidth);
  if (development)
    lfcam::development(exposure, bandwidths);
  else
    lfcam::report(exposure, bandwidths.front());
  int count = int(rest.size());
  benchmark::Initialize(&count, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
