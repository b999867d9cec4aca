// lfcam denoise on simulator captures with the sensor's noise model (issue 20, item 4): the people
// scene traced once through the people tests' camera (9x9 views of 80x80), each frame the sensor
// model with its own noise, decoded on the true grid (the experiments' capture chain), against the
// noise-free frame of the same trace. The passband is the cards' disparity range, 0.25 wider on each
// side (from the scene's geometry); the bandwidth is the default. Per card, on the pixels well
// inside it:
//   - SNR (mean over rms error against the noise-free capture) of the centre view and of the photo
//     refocused at the card's disparity, before and after the filter;
//   - the noise alone: rms of noisy minus noise-free, before; of filtered noisy minus filtered
//     noise-free, after (the filter is linear);
//   - sharpness: gradient energy of the noise-free capture's centre view and photo, filtered over
//     unfiltered (noise would count as detail on the noisy ones); and, first, the refocused photo's
//     over the centre view's: how much of the centre view's detail the views share.
// Run: build/bench/denoise_bench [--exposure E] [--microlenses N] (default: exposures 1 and 0.1, a
// ten times shorter one; 80 microlenses across); then the filter's time on one noisy capture.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "experiments/experiment_support.hpp"
#include "lfcam/analysis.hpp"
#include "lfcam/denoise.hpp"
#include "lfcam/depth.hpp"
#include "lfcam/refocus.hpp"
#include "lfcam/scene.hpp"
#include "people_camera.hpp"
#include "people_cards.hpp"

namespace lfcam {
namespace {

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

// Mean squared forward difference (x and y) of channel 0 over the mask.
double gradientEnergy(const Image& image, const Image& mask) {
  double sum = 0;
  long count = 0;
  for (int y = 0; y + 1 < image.height(); ++y)
    for (int x = 0; x + 1 < image.width(); ++x)
      if (mask.at(x, y, 0) > 0) {
        const double gx = image.at(x + 1, y, 0) - image.at(x, y, 0), gy = image.at(x, y + 1, 0) - image.at(x, y, 0);
        sum += gx * gx + gy * gy, ++count;
      }
  return count ? sum / double(count) : 0;
}

Image centreView(const LightField& lightField) {
  return lightField.subApertureImage((lightField.nu() - 1) / 2, (lightField.nv() - 1) / 2);
}

double snr(const Image& frame, const Image& standard, const Image& mask) {
  return signalToNoise(frame, standard, &mask)->snr;
}

void measure(double exposure, int microlenses) {
  CameraModel camera = test::peopleCamera(microlenses);
  camera.sensor.exposure = exposure;
  const Scene scene = *builtinScene("people", camera);
  auto traced = experiments::traceCapture(scene, camera, 64);
  if (!traced) throw std::runtime_error(traced.error().message);
  auto clean = experiments::captureLightField(*traced, false, 0);
  auto noisy = experiments::captureLightField(*traced, true, 7);
  if (!clean || !noisy) throw std::runtime_error("capture failed");
  const Image depth = *idealDepth(scene, camera);
  const std::vector<test::Card> cards = test::sceneCards(scene, depth, *clean->metadata.optics);
  DenoiseOptions options;
  options.slopeMin = INFINITY, options.slopeMax = -INFINITY;
  for (const test::Card& card : cards)
    options.slopeMin = std::min(options.slopeMin, card.disparity - 0.25),
    options.slopeMax = std::max(options.slopeMax, card.disparity + 0.25);
  auto cleanFiltered = denoise(*clean, options);
  auto noisyFiltered = denoise(*noisy, options);
  if (!cleanFiltered || !noisyFiltered) throw std::runtime_error("denoise failed");

  std::printf("\nexposure %.2f (%d x %d views of %d x %d), passband %.2f:%.2f, bandwidth %.2f\n", exposure, clean->nu(),
              clean->nv(), clean->ns(), clean->nt(), options.slopeMin, options.slopeMax, options.bandwidth);
  std::printf(
      "| card | disparity | refocused / centre sharpness | centre view SNR before | after | noise rms before | after | "
      "sharpness kept | "
      "refocused SNR before | after | noise rms before | after | sharpness kept |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const Image centreClean = centreView(*clean), centreNoisy = centreView(*noisy);
  const Image centreCleanFiltered = centreView(*cleanFiltered), centreNoisyFiltered = centreView(*noisyFiltered);
  for (const test::Card& card : cards) {
    const Image mask = maskOf(card, depth.width(), clean->ns(), clean->nt());
    const Image photoClean = refocus(*clean, card.disparity), photoNoisy = refocus(*noisy, card.disparity);
    const Image photoCleanFiltered = refocus(*cleanFiltered, card.disparity);
    const Image photoNoisyFiltered = refocus(*noisyFiltered, card.disparity);
    // SNR against the noise-free capture, and the noise alone (the filter is linear: the filtered
    // noisy capture minus the filtered noise-free one).
    auto row = [&](const Image& noisyBefore, const Image& cleanBefore, const Image& noisyAfter,
                   const Image& cleanAfter) {
      const double sharpness = gradientEnergy(cleanAfter, mask) / gradientEnergy(cleanBefore, mask);
      std::printf(" %.1f | %.1f | %.4f | %.4f | %.1f %% |", snr(noisyBefore, cleanBefore, mask),
                  snr(noisyAfter, cleanBefore, mask), signalToNoise(noisyBefore, cleanBefore, &mask)->noise,
                  signalToNoise(noisyAfter, cleanAfter, &mask)->noise, 100 * sharpness);
    };
    std::printf("| %s | %+.2f | %.1f %% |", card.name.c_str(), card.disparity,
                100 * gradientEnergy(photoClean, mask) / gradientEnergy(centreClean, mask));
    row(centreNoisy, centreClean, centreNoisyFiltered, centreCleanFiltered);
    row(photoNoisy, photoClean, photoNoisyFiltered, photoCleanFiltered);
    std::printf("\n");
  }
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
  std::vector<double> exposures;
  int microlenses = 80;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--exposure") == 0) exposures.push_back(std::atof(argv[i + 1]));
    if (std::strcmp(argv[i], "--microlenses") == 0) microlenses = std::atoi(argv[i + 1]);
  }
  if (exposures.empty()) exposures = {1.0, 0.1};
  for (double exposure : exposures) lfcam::measure(exposure, microlenses);
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--exposure") == 0 || std::strcmp(argv[i], "--microlenses") == 0) {
      ++i;
      continue;
    }
    rest.push_back(argv[i]);
  }
  int count = int(rest.size());
  benchmark::Initialize(&count, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
