// Turbo colour map (color_map.hpp).
#include "lfcam/io/color_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lfcam/io/image_io.hpp"

namespace lfcam {

// The polynomial fit of Turbo published with it (degree 5 per channel, sRGB-encoded output).
void turbo(double x, float rgb[3]) {
  x = std::clamp(std::isfinite(x) ? x : 0.0, 0.0, 1.0);
  const double x2 = x * x, x3 = x2 * x, x4 = x3 * x, x5 = x4 * x;
  const double r =
      0.13572138 + 4.61539260 * x - 42.66032258 * x2 + 132.13108234 * x3 - 152.94239396 * x4 + 59.28637943 * x5;
  const double g = 0.09140261 + 2.19418839 * x + 4.84296658 * x2 - 14.18503333 * x3 + 4.27729857 * x4 + 2.82956604 * x5;
  const double b =
      0.10667330 + 12.64194608 * x - 60.58204836 * x2 + 110.36276771 * x3 - 89.90310912 * x4 + 27.34824973 * x5;
  const double encoded[3] = {r, g, b};
  for (int c = 0; c < 3; ++c) rgb[c] = linearFromSrgb(float(std::clamp(encoded[c], 0.0, 1.0)));
}

Image colorMap(const Image& scalar, double low, double high) {
  Image out(scalar.width(), scalar.height(), 3);
  if (scalar.empty()) return out;
  const float* values = scalar.plane(0);
  if (!(low < high)) {
    low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::size_t i = 0; i < scalar.planeSize(); ++i)
      if (std::isfinite(values[i])) low = std::min(low, double(values[i])), high = std::max(high, double(values[i]));
    if (!(low < high)) high = low + 1;  // constant (or empty) map: one colour
  }
  for (std::size_t i = 0; i < scalar.planeSize(); ++i) {
    float rgb[3] = {0, 0, 0};
    if (std::isfinite(values[i])) turbo((values[i] - low) / (high - low), rgb);
    for (int c = 0; c < 3; ++c) out.plane(c)[i] = rgb[c];
  }
  return out;
}

}  // namespace lfcam
