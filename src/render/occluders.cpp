// The nearest surface each view sees (occluders.hpp).
#include "render/occluders.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.hpp"

namespace lfcam {

Occluders::Occluders(const LightField& lightField, const Image& disparity)
    : nu_(lightField.nu()), ns_(lightField.ns()), pixels_(std::size_t(lightField.ns()) * lightField.nt()) {
  const int ns = lightField.ns(), nt = lightField.nt();
  const std::size_t views = std::size_t(nu_) * lightField.nv();
  nearest_.assign(views * pixels_, -std::numeric_limits<float>::infinity());
  parallelFor(0, views, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view) {
      const double uc = lightField.uFromCentre(int(view % nu_)), vc = lightField.vFromCentre(int(view / nu_));
      float* seen = nearest_.data() + view * pixels_;
      for (int y = 0; y < nt; ++y)
        for (int x = 0; x < ns; ++x) {
          const float d = disparity.at(x, y, 0);
          const double column = std::floor(x - uc * d), row = std::floor(y - vc * d);
          for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
              const double c = column + i, r = row + j;
              if (c < 0 || c >= ns || r < 0 || r >= nt) continue;
              float& at = seen[std::size_t(r) * ns + std::size_t(c)];
              at = std::max(at, d);
            }
        }
    }
  });
}

}  // namespace lfcam
