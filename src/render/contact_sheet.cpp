#include "lfcam/render/contact_sheet.hpp"

#include <algorithm>

#include "core/parallel.hpp"

namespace lfcam {

Image contactSheet(const LightField& lf, const ContactSheetOptions& options) {
  const int gap = std::max(0, options.gap);
  // The smallest whole shrink factor that fits the sheet into maxWidth.
  int factor = 1;
  while (factor < lf.ns() && lf.nu() * (lf.ns() / factor) + (lf.nu() + 1) * gap > std::max(options.maxWidth, 1))
    ++factor;
  const int tileW = std::max(1, lf.ns() / factor), tileH = std::max(1, lf.nt() / factor);
  Image sheet(lf.nu() * tileW + (lf.nu() + 1) * gap, lf.nv() * tileH + (lf.nv() + 1) * gap, lf.channels());
  std::fill(sheet.pixels().begin(), sheet.pixels().end(), options.background);

  const float norm = 1.0f / float(factor * factor);
  parallelFor(0, lf.shape().views(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view) {
      const int u = int(view % lf.nu()), v = int(view / lf.nu());
      const int x0 = gap + u * (tileW + gap), y0 = gap + v * (tileH + gap);
      for (int c = 0; c < lf.channels(); ++c) {
        const float* plane = lf.plane(u, v, c);
        for (int y = 0; y < tileH; ++y)
          for (int x = 0; x < tileW; ++x) {
            float sum = 0;  // box filter over the factor x factor block
            for (int dy = 0; dy < factor; ++dy)
              for (int dx = 0; dx < factor; ++dx)
                sum += plane[std::size_t(y * factor + dy) * lf.ns() + x * factor + dx];
            sheet.at(x0 + x, y0 + y, c) = sum * norm;
          }
      }
    }
  });
  return sheet;
}

}  // namespace lfcam
