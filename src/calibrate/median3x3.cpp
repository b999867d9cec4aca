// 3x3 median: a sorting network over the interior (vectorised by the compiler), the clipped
// window at the borders.
#include <algorithm>
#include <utility>

#include "lfcam/calibrate.hpp"
#include "lfcam/parallel.hpp"

namespace lfcam {

namespace {

// Median of the window clipped to the image.
float clippedMedian(const Image& image, int x, int y) {
  float values[9];
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int px = x + dx, py = y + dy;
      if (px < 0 || py < 0 || px >= image.width() || py >= image.height()) continue;
      values[count++] = image.at(px, py, 0);
    }
  for (int a = 1; a < count; ++a)  // insertion sort: at most nine values
    for (int b = a; b > 0 && values[b - 1] > values[b]; --b) std::swap(values[b - 1], values[b]);
  // Even counts: the mean of the two middle values, so the result is symmetric.
  return count & 1 ? values[count / 2] : 0.5f * (values[count / 2 - 1] + values[count / 2]);
}

inline void order(float& a, float& b) {
  const float lo = std::min(a, b), hi = std::max(a, b);
  a = lo;
  b = hi;
}

}  // namespace

Image median3x3Reference(const Image& image) {
  Image out(image.width(), image.height(), 1);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) out.at(x, y, 0) = clippedMedian(image, x, y);
  return out;
}

Image median3x3(const Image& image) {
  const int width = image.width(), height = image.height();
  Image out(width, height, 1);
  parallelFor(0, std::size_t(height), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y) {
      float* o = out.row(y, 0);
      if (y == 0 || y == height - 1 || width < 3) {
        for (int x = 0; x < width; ++x) o[x] = clippedMedian(image, x, y);
        continue;
      }
      const float* r0 = image.row(y - 1, 0);
      const float* r1 = image.row(y, 0);
      const float* r2 = image.row(y + 1, 0);
      o[0] = clippedMedian(image, 0, y);
      o[width - 1] = clippedMedian(image, width - 1, y);
      for (int x = 1; x < width - 1; ++x) {
        // The 19-exchange median-of-9 network (Paeth).
        float p0 = r0[x - 1], p1 = r0[x], p2 = r0[x + 1], p3 = r1[x - 1], p4 = r1[x], p5 = r1[x + 1];
        float p6 = r2[x - 1], p7 = r2[x], p8 = r2[x + 1];
        order(p1, p2); order(p4, p5); order(p7, p8);
        order(p0, p1); order(p3, p4); order(p6, p7);
        order(p1, p2); order(p4, p5); order(p7, p8);
        order(p0, p3); order(p5, p8); order(p4, p7);
        order(p3, p6); order(p1, p4); order(p2, p5);
        order(p4, p7); order(p4, p2); order(p6, p4);
        order(p4, p2);
        o[x] = p4;
      }
    }
  });
  return out;
}

}  // namespace lfcam
