// 3x3 median: a sorting network over the interior (vectorised by the compiler), the clipped
// window at the borders; per row, so that calibration's preparation can stream rows through it.
#include <algorithm>
#include <utility>

#include "calibrate/calibrate_internal.hpp"
#include "core/parallel.hpp"
#include "lfcam/calibrate/calibrate.hpp"

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

Image median3x3(const Image& image) {
  const int width = image.width(), height = image.height();
  Image out(width, height, 1);
  parallelFor(0, std::size_t(height), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y)
      calibrate_detail::median3x3Row(y > 0 ? image.row(y - 1, 0) : nullptr, image.row(y, 0),
                                     y + 1 < height ? image.row(y + 1, 0) : nullptr, width, 0, width, out.row(y, 0));
  });
  return out;
}

namespace calibrate_detail {

Image median3x3Reference(const Image& image) {
  Image out(image.width(), image.height(), 1);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) out.at(x, y, 0) = clippedMedian(image, x, y);
  return out;
}

void median3x3Row(const float* above, const float* row, const float* below, int width, int x0, int x1, float* out) {
  // Median of the window clipped to the image (borders).
  const auto clipped = [&](int x) {
    float values[9];
    int count = 0;
    for (const float* r : {above, row, below}) {
      if (!r) continue;
      for (int px = std::max(x - 1, 0); px <= std::min(x + 1, width - 1); ++px) values[count++] = r[px];
    }
    for (int a = 1; a < count; ++a)  // insertion sort: at most nine values
      for (int b = a; b > 0 && values[b - 1] > values[b]; --b) std::swap(values[b - 1], values[b]);
    return count & 1 ? values[count / 2] : 0.5f * (values[count / 2 - 1] + values[count / 2]);
  };
  if (!above || !below || width < 3) {
    for (int x = x0; x < x1; ++x) out[x] = clipped(x);
    return;
  }
  if (x0 == 0) out[0] = clipped(0);
  if (x1 == width) out[width - 1] = clipped(width - 1);
  const float* r0 = above;
  const float* r1 = row;
  const float* r2 = below;
  for (int x = std::max(x0, 1); x < std::min(x1, width - 1); ++x) {
    // The 19-exchange median-of-9 network (Paeth).
    float p0 = r0[x - 1], p1 = r0[x], p2 = r0[x + 1], p3 = r1[x - 1], p4 = r1[x], p5 = r1[x + 1];
    float p6 = r2[x - 1], p7 = r2[x], p8 = r2[x + 1];
    order(p1, p2);
    order(p4, p5);
    order(p7, p8);
    order(p0, p1);
    order(p3, p4);
    order(p6, p7);
    order(p1, p2);
    order(p4, p5);
    order(p7, p8);
    order(p0, p3);
    order(p5, p8);
    order(p4, p7);
    order(p3, p6);
    order(p1, p4);
    order(p2, p5);
    order(p4, p7);
    order(p4, p2);
    order(p6, p4);
    order(p4, p2);
    out[x] = p4;
  }
}

}  // namespace calibrate_detail

}  // namespace lfcam
