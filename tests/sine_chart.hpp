// A simulated chart of vertical sine gratings, one frequency per horizontal band, and the
// modulation each band keeps in a photograph of it: the sharpness target of the upsampled refocus
// test and of bench/denoise_bench.cpp (MTF50 at the chart's depth).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/simulate/camera_model.hpp"
#include "lfcam/simulate/scene.hpp"

namespace lfcam::test {

// The chart: vertical sine gratings of contrast 0.4 / 0.5 in horizontal bands, one frequency per
// band (cycles per microlens of the refocused photograph at the chart's distance), wide enough to
// fill the field.
inline constexpr double kChartMean = 0.5, kChartAmplitude = 0.4;
inline const std::vector<double> kChartFrequencies{0.15, 0.25, 0.35, 0.45, 0.55, 0.65, 0.75, 0.85};

inline Scene sineChartScene(const CameraModel& camera, double distanceMm) {
  const auto counts = camera.microlensCounts();
  const double patch = camera.microlenses->pitchMm * distanceMm / camera.mainLens.imageDistanceMm();
  const double across = 1.25 * counts[0];  // microlenses the chart spans
  const int texels = 16, bandTexels = 8;   // per microlens across; per band down
  auto image = std::make_shared<Image>(int(across * texels), int(kChartFrequencies.size()) * bandTexels, 1);
  for (int y = 0; y < image->height(); ++y)
    for (int x = 0; x < image->width(); ++x) {
      const double f = kChartFrequencies[y / bandTexels], position = (x + 0.5) / texels;
      image->at(x, y, 0) = float(kChartMean + kChartAmplitude * std::sin(2 * M_PI * f * position));
    }
  Plane chart;
  chart.name = "sine chart";
  chart.centreMm = {0, 0, distanceMm};
  chart.widthMm = across * patch;
  chart.heightMm = counts[1] * patch;  // the bands fill the field from top to bottom
  chart.texture.kind = TextureKind::Image;
  chart.texture.image = image;
  Scene scene;
  scene.name = "sine chart";
  scene.planes.push_back(chart);
  scene.background = {kChartMean, kChartMean, kChartMean};
  scene.camera = camera;
  return scene;
}

// Modulation at `frequency` (cycles per microlens) of band `band`'s grating in `photo` (factor K
// finer than the microlenses): the amplitude of the least-squares fit of mean + a cos + b sin over
// the band's inner rows and columns, over the chart's contrast.
inline double modulationAt(const Image& photo, int factor, int band, double frequency) {
  const double bandRows = double(photo.height()) / kChartFrequencies.size();
  // Normal equations of the three-term fit, summed over the band's inner rows.
  double ata[3][3] = {}, atb[3] = {};
  const int y0 = int(std::ceil((band + 0.25) * bandRows)), y1 = int(std::floor((band + 0.75) * bandRows));
  const int x0 = photo.width() / 8, x1 = photo.width() - photo.width() / 8;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const double position = (x + 0.5) / factor;  // microlenses
      const double basis[3] = {1, std::cos(2 * M_PI * frequency * position), std::sin(2 * M_PI * frequency * position)};
      for (int i = 0; i < 3; ++i) {
        atb[i] += basis[i] * photo.at(x, y, 0);
        for (int j = 0; j < 3; ++j) ata[i][j] += basis[i] * basis[j];
      }
    }
  // Gaussian elimination of the 3 x 3 system.
  for (int i = 0; i < 3; ++i)
    for (int k = i + 1; k < 3; ++k) {
      const double m = ata[k][i] / ata[i][i];
      for (int j = i; j < 3; ++j) ata[k][j] -= m * ata[i][j];
      atb[k] -= m * atb[i];
    }
  double c[3];
  for (int i = 2; i >= 0; --i) {
    double sum = atb[i];
    for (int j = i + 1; j < 3; ++j) sum -= ata[i][j] * c[j];
    c[i] = sum / ata[i][i];
  }
  return std::hypot(c[1], c[2]) / c[0] / (kChartAmplitude / kChartMean);
}

// Each band's modulation at its own frequency; 0 for a grating above the photograph's Nyquist
// frequency (K / 2 cycles per microlens), which it cannot hold.
inline std::vector<double> modulationPerBand(const Image& photo, int factor) {
  std::vector<double> modulation;
  for (std::size_t band = 0; band < kChartFrequencies.size(); ++band) {
    const double f = kChartFrequencies[band];
    modulation.push_back(f < 0.5 * factor ? modulationAt(photo, factor, int(band), f) : 0.0);
  }
  return modulation;
}

// The frequency where the modulation first falls to 0.5, interpolated between bands; the highest
// frequency the photograph holds (its Nyquist) when it never does below it.
inline double mtf50(const std::vector<double>& modulation, int factor) {
  for (std::size_t k = 1; k < modulation.size(); ++k)
    if (modulation[k] < 0.5 && modulation[k - 1] >= 0.5) {
      const double t = (modulation[k - 1] - 0.5) / (modulation[k - 1] - modulation[k]);
      return std::min(0.5 * factor, kChartFrequencies[k - 1] + t * (kChartFrequencies[k] - kChartFrequencies[k - 1]));
    }
  return modulation.front() < 0.5 ? kChartFrequencies.front() : 0.5 * factor;
}
}  // namespace lfcam::test
