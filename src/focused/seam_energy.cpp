#include "lfcam/focused/seam_energy.hpp"

#include <cmath>
#include <complex>
#include <vector>

namespace lfcam {

double seamEnergy(const Image& photo, const FocusedCalibration& calibration, double pixelsPerLens) {
  const int w = photo.width(), h = photo.height();
  if (w < 3 || h < 3) return 0;
  // The lattice's steps in photograph pixels, and the reciprocal vectors (a_i . b_j = 2 pi delta_ij).
  const LensletGrid& grid = calibration.grid;
  const double scale = pixelsPerLens / grid.pitchX, c = std::cos(grid.rotationRad), s = std::sin(grid.rotationRad);
  const double half = grid.packing == Packing::Hexagonal ? 0.5 : 0.0;
  const double a1x = grid.pitchX * c * scale, a1y = grid.pitchX * s * scale;
  const double a2x = (half * grid.pitchX * c - grid.pitchY * s) * scale;
  const double a2y = (half * grid.pitchX * s + grid.pitchY * c) * scale;
  const double det = a1x * a2y - a1y * a2x;
  const double b1x = 2 * M_PI * a2y / det, b1y = -2 * M_PI * a2x / det;
  const double b2x = -2 * M_PI * a1y / det, b2y = 2 * M_PI * a1x / det;
  std::vector<std::array<double, 2>> frequencies{{b1x, b1y}, {b2x, b2y}};
  if (grid.packing == Packing::Hexagonal) frequencies.push_back({b1x - b2x, b1y - b2y});

  std::vector<double> grey(std::size_t(w) * h, 0.0), edges(grey.size(), 0.0);
  for (int ch = 0; ch < photo.channels(); ++ch)
    for (std::size_t k = 0; k < grey.size(); ++k) grey[k] += photo.plane(ch)[k] / photo.channels();
  double mean = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const std::size_t k = std::size_t(y) * w + x;
      edges[k] = 0.5 * std::hypot(grey[k + 1] - grey[k - 1], grey[k + w] - grey[k - w]);
      mean += edges[k] / (double(w - 2) * (h - 2));
    }
  double power = 0;
  for (const auto& k : frequencies) {
    std::complex<double> sum = 0;
    for (int y = 1; y + 1 < h; ++y) {
      const double wy = 0.5 - 0.5 * std::cos(2 * M_PI * y / (h - 1));
      for (int x = 1; x + 1 < w; ++x) {
        const double wx = 0.5 - 0.5 * std::cos(2 * M_PI * x / (w - 1));
        sum += wx * wy * (edges[std::size_t(y) * w + x] - mean) * std::polar(1.0, -(k[0] * x + k[1] * y));
      }
    }
    power += std::norm(sum) / (double(w) * h);
  }
  return power;
}

}  // namespace lfcam
