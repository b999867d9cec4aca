#include "lfcam/focused/micro_image_sharpness.hpp"

#include <cmath>

#include "core/parallel.hpp"

namespace lfcam {

std::vector<float> microImageSharpness(const Image& image, const FocusedCalibration& calibration) {
  const LensletGrid& grid = calibration.grid;
  std::vector<float> sharpness(std::size_t(grid.columns) * grid.rows, 0.0f);
  const int w = image.width(), h = image.height();
  auto grey = [&](int x, int y) {
    double sum = 0;
    for (int c = 0; c < image.channels(); ++c) sum += image.at(x, y, c);
    return sum / image.channels();
  };
  const double radius = 0.5 * calibration.diameterPx() - calibration.borderPx - 1;  // the Laplacian's reach
  parallelFor(0, std::size_t(grid.rows), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j)
      for (int i = 0; i < grid.columns; ++i) {
        const auto c = grid.centre(i, int(j));
        if (c[0] - radius < 1 || c[1] - radius < 1 || c[0] + radius > w - 1 || c[1] + radius > h - 1) continue;
        double s1 = 0, s2 = 0, laplacian = 0;
        int n = 0;
        for (int y = int(std::ceil(c[1] - radius)); y <= int(std::floor(c[1] + radius)); ++y)
          for (int x = int(std::ceil(c[0] - radius)); x <= int(std::floor(c[0] + radius)); ++x) {
            const double dx = x + 0.5 - c[0], dy = y + 0.5 - c[1];
            if (dx * dx + dy * dy > radius * radius) continue;
            const double g = grey(x, y);
            const double l = grey(x - 1, y) + grey(x + 1, y) + grey(x, y - 1) + grey(x, y + 1) - 4 * g;
            s1 += g;
            s2 += g * g;
            laplacian += l * l;
            ++n;
          }
        const double variance = n > 0 ? s2 / n - (s1 / n) * (s1 / n) : 0;
        if (variance > 1e-8) sharpness[j * std::size_t(grid.columns) + i] = float(laplacian / n / variance);
      }
  });
  return sharpness;
}

}  // namespace lfcam
