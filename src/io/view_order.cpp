#include "io/view_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lfcam/io/image_io.hpp"

namespace lfcam::io {

namespace {

// Channel mean divided by the image mean: views of a vignetted aperture differ in brightness.
Image normalisedLuminance(const Image& image) {
  Image luminance(image.width(), image.height(), 1);
  double total = 0;
  for (std::size_t i = 0; i < luminance.planeSize(); ++i) {
    float sum = 0;
    for (int c = 0; c < image.channels(); ++c) sum += image.plane(c)[i];
    luminance.pixels()[i] = sum;
    total += sum;
  }
  const float scale = total > 0 ? float(luminance.planeSize() / total) : 1.0f;
  for (float& value : luminance.pixels()) value *= scale;
  return luminance;
}

// Squared difference between the block [x0, x0 + size) x [y0, y0 + size) of a and the same block
// of b shifted by (dx, dy).
double blockDifference(const Image& a, const Image& b, int x0, int y0, int size, int dx, int dy) {
  double sum = 0;
  for (int y = y0; y < y0 + size; ++y)
    for (int x = x0; x < x0 + size; ++x) {
      const double d = a.at(x, y, 0) - b.at(x + dx, y + dy, 0);
      sum += d * d;
    }
  return sum;
}

}  // namespace

double horizontalParallaxEvidence(const Image& a, const Image& b) {
  const int size = std::min({a.width(), a.height(), b.width(), b.height()});
  const int reach = std::clamp(size / 16, 1, 16);  // largest shift tried, pixels
  if (size <= 2 * reach + 16 || a.width() != b.width() || a.height() != b.height()) return 0;
  const Image la = normalisedLuminance(a), lb = normalisedLuminance(b);
  // Block by block, since surfaces at different depths shift by different amounts (and in
  // opposite directions on either side of the plane in focus).
  constexpr int block = 16;
  double horizontal = 0, vertical = 0, unshifted = 0;
  for (int y0 = reach; y0 + block + reach <= la.height(); y0 += block)
    for (int x0 = reach; x0 + block + reach <= la.width(); x0 += block) {
      double bestHorizontal = std::numeric_limits<double>::max(), bestVertical = bestHorizontal;
      for (int shift = -reach; shift <= reach; ++shift) {
        bestHorizontal = std::min(bestHorizontal, blockDifference(la, lb, x0, y0, block, shift, 0));
        bestVertical = std::min(bestVertical, blockDifference(la, lb, x0, y0, block, 0, shift));
      }
      horizontal += bestHorizontal, vertical += bestVertical;
      unshifted += blockDifference(la, lb, x0, y0, block, 0, 0);
    }
  return unshifted > 0 ? (vertical - horizontal) / unshifted : 0.0;
}

Result<ViewNumberOrder> detectViewNumberOrder(const ViewGrid& grid) {
  if (grid.nu < 2 || grid.nv < 2) return ViewNumberOrder::RowFirst;
  // Views a fifth of the way in from each end: far apart, but clear of the dark corners of a
  // vignetted aperture.
  auto inset = [](int n) { return std::min(n / 5, (n - 1) / 2); };
  const int u0 = inset(grid.nu), u1 = grid.nu - 1 - u0, v0 = inset(grid.nv), v1 = grid.nv - 1 - v0;
  auto view = [&](int u, int v) { return readImage(grid.files[std::size_t(v) * grid.nu + u]); };
  auto left = view(u0, grid.nv / 2), right = view(u1, grid.nv / 2);
  auto top = view(grid.nu / 2, v0), bottom = view(grid.nu / 2, v1);
  for (const auto* image : {&left, &right, &top, &bottom})
    if (!*image) return image->error();
  const double alongRow = horizontalParallaxEvidence(*left, *right);
  const double alongColumn = horizontalParallaxEvidence(*top, *bottom);
  // Swap only on clear evidence from both pairs; anything less keeps the usual order.
  constexpr double clear = 0.05;
  return alongRow < -clear && alongColumn > clear ? ViewNumberOrder::ColumnFirst : ViewNumberOrder::RowFirst;
}

}  // namespace lfcam::io
