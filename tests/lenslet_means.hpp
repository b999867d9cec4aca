// The raw's own picture, which a decoded photo must match as it lies (not turned): each
// microlens image averaged, laid out as the microlenses lie in the file; and the correlation
// that compares them.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "lfcam/calibrate/lenslet_grid.hpp"
#include "lfcam/core/image.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam::test {

// Pearson correlation of the pairs added.
class Correlation {
 public:
  void add(double p, double q) { sa_ += p, sb_ += q, saa_ += p * p, sbb_ += q * q, sab_ += p * q, ++n_; }
  long count() const { return n_; }
  double value() const {
    const double n = double(std::max(1L, n_));
    const double cov = sab_ / n - sa_ / n * sb_ / n;
    const double var = (saa_ / n - sa_ / n * sa_ / n) * (sbb_ / n - sb_ / n * sb_ / n);
    return var > 0 ? cov / std::sqrt(var) : 0.0;
  }

 private:
  double sa_ = 0, sb_ = 0, saa_ = 0, sbb_ = 0, sab_ = 0;
  long n_ = 0;
};

struct LensletMeans {
  Image means;                 // grid.columns x grid.rows, 1 channel
  std::vector<bool> complete;  // the microlens's disc lies wholly inside the raw
};

// Each microlens image of `raw` over a disc of 0.4 pitch, divided by the white image's response
// there; both less `dark` when given, else less their black levels.
inline LensletMeans lensletMeans(const RawImage& raw, const RawImage& white, const LensletGrid& grid,
                                 const RawImage* dark = nullptr) {
  LensletMeans out{Image(grid.columns, grid.rows, 1), std::vector<bool>(std::size_t(grid.columns) * grid.rows)};
  const Image& r = raw.mosaic;
  auto floor = [&](const RawImage& image, int x, int y) { return dark ? dark->mosaic.at(x, y, 0) : image.blackLevel; };
  const double radius = 0.4 * grid.pitchX;
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      const auto c = grid.centre(i, j);
      double light = 0, response = 0;
      bool inside = true;
      for (int y = int(c[1] - radius); y <= int(c[1] + radius); ++y)
        for (int x = int(c[0] - radius); x <= int(c[0] + radius); ++x) {
          if (std::hypot(x + 0.5 - c[0], y + 0.5 - c[1]) > radius) continue;
          if (x < 0 || y < 0 || x >= r.width() || y >= r.height()) {
            inside = false;
            continue;
          }
          light += r.at(x, y, 0) - floor(raw, x, y);
          response += white.mosaic.at(x, y, 0) - floor(white, x, y);
        }
      out.means.at(i, j, 0) = response > 0 ? float(light / response) : 0.0f;
      out.complete[std::size_t(j) * grid.columns + i] = inside && response > 0;
    }
  return out;
}

}  // namespace lfcam::test
