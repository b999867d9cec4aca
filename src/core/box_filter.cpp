#include "core/box_filter.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/target_clones.hpp"

namespace lfcam {

// Two passes of running sums (rows, then columns), each in double to keep long sums exact
// enough; the window is clipped at the borders and the mean taken over what remains, as the sum
// times the count's reciprocal (a division per pixel was half the filter's time). The rows' means
// live in a ring of the 2 radius + 2 rows that the column sums still add or take off, which stays
// in cache, not in a whole plane allocated and zeroed per call.
LFCAM_CLONES void boxFilter(const float* in, float* out, int width, int height, int radius) {
  const int ringRows = std::min(2 * radius + 2, height);
  std::vector<float> ring(std::size_t(width) * std::max(ringRows, 1));
  std::vector<double> prefix(std::size_t(width) + 1), inverse(std::size_t(std::max(width, height)) + 1);
  for (std::size_t count = 1; count < inverse.size(); ++count) inverse[count] = 1.0 / double(count);
  // Columns [interiorBegin, interiorEnd) see the whole window.
  const int interiorBegin = std::min(radius, width), interiorEnd = std::max(interiorBegin, width - radius);
  const double interiorScale = inverse[std::min(2 * radius + 1, width)];
  const auto horizontal = [&](int y) { return ring.data() + std::size_t(y % ringRows) * width; };
  // Row y's horizontal means into its place in the ring.
  const auto rowMeans = [&](int y) {
    const float* row = in + std::size_t(y) * width;
    prefix[0] = 0;
    for (int x = 0; x < width; ++x) prefix[x + 1] = prefix[x] + row[x];
    float* target = horizontal(y);
    const auto clipped = [&](int x) {
      const int x0 = std::max(0, x - radius), x1 = std::min(width, x + radius + 1);
      target[x] = float((prefix[x1] - prefix[x0]) * inverse[x1 - x0]);
    };
    for (int x = 0; x < interiorBegin; ++x) clipped(x);
    for (int x = interiorBegin; x < interiorEnd; ++x)
      target[x] = float((prefix[x + radius + 1] - prefix[x - radius]) * interiorScale);
    for (int x = interiorEnd; x < width; ++x) clipped(x);
  };
  // Columns: running sums along y, all columns of a row at once (contiguous).
  std::vector<double> columnSum(width, 0.0);
  const auto addRow = [&](int y) {
    rowMeans(y);
    const float* row = horizontal(y);
    for (int x = 0; x < width; ++x) columnSum[x] += row[x];
  };
  const auto subtractRow = [&](int y) {
    const float* row = horizontal(y);
    for (int x = 0; x < width; ++x) columnSum[x] -= row[x];
  };
  for (int y = 0; y < std::min(radius, height); ++y) addRow(y);
  for (int y = 0; y < height; ++y) {
    if (y + radius < height) addRow(y + radius);
    if (y - radius - 1 >= 0) subtractRow(y - radius - 1);
    const double scale = inverse[std::min(height, y + radius + 1) - std::max(0, y - radius)];
    float* target = out + std::size_t(y) * width;
    for (int x = 0; x < width; ++x) target[x] = float(columnSum[x] * scale);
  }
}

}  // namespace lfcam
