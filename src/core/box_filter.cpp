#include "core/box_filter.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace lfcam {

// Two passes of running sums (rows, then columns), each in double to keep long sums exact
// enough; the window is clipped at the borders and the mean taken over what remains.
void boxFilter(const float* in, float* out, int width, int height, int radius) {
  std::vector<float> horizontal(std::size_t(width) * height);
  std::vector<double> prefix(std::size_t(std::max(width, height)) + 1);
  for (int y = 0; y < height; ++y) {
    const float* row = in + std::size_t(y) * width;
    prefix[0] = 0;
    for (int x = 0; x < width; ++x) prefix[x + 1] = prefix[x] + row[x];
    float* target = horizontal.data() + std::size_t(y) * width;
    for (int x = 0; x < width; ++x) {
      const int x0 = std::max(0, x - radius), x1 = std::min(width, x + radius + 1);
      target[x] = float((prefix[x1] - prefix[x0]) / (x1 - x0));
    }
  }
  // Columns: running sums along y, all columns of a row at once (contiguous).
  std::vector<double> columnSum(width, 0.0);
  auto addRow = [&](int y, double sign) {
    const float* row = horizontal.data() + std::size_t(y) * width;
    for (int x = 0; x < width; ++x) columnSum[x] += sign * row[x];
  };
  for (int y = 0; y < std::min(radius, height); ++y) addRow(y, 1);
  for (int y = 0; y < height; ++y) {
    if (y + radius < height) addRow(y + radius, 1);
    if (y - radius - 1 >= 0) addRow(y - radius - 1, -1);
    const int count = std::min(height, y + radius + 1) - std::max(0, y - radius);
    float* target = out + std::size_t(y) * width;
    for (int x = 0; x < width; ++x) target[x] = float(columnSum[x] / count);
  }
}

}  // namespace lfcam
