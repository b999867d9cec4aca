// The scalar row of fine_cost_row.hpp.
#include "edof/fine_cost_row.hpp"

#include <cstddef>

#include "core/bilinear.hpp"

namespace lfcam::edof {

void fineCostRowReference(const FineCostViews& views, int y, const float* disparity, double offset, float* const* out) {
  const int ns = views.ns, nt = views.nt, channels = views.channels;
  const std::size_t subsets = views.viewsIn.size();
  const double referenceUc = views.uc[0], referenceVc = views.vc[0];
  std::vector<float> reference(channels);
  for (int x = 0; x < ns; ++x) {
    const std::size_t p = std::size_t(y) * ns + x;
    const double d = disparity[x] + offset;
    const double referenceLoss = interpolationNoiseLoss(views.noise, -referenceUc * d, -referenceVc * d);
    for (int c = 0; c < channels; ++c)
      reference[c] = bilinearSample(views.planes[c], ns, nt, x - referenceUc * d, double(y) - referenceVc * d);
    float sums[kMaxCostSubsets] = {};
    for (std::size_t i = 1; i < views.uc.size(); ++i) {
      const double uc = views.uc[i], vc = views.vc[i];
      float squares = 0;
      for (int c = 0; c < channels; ++c) {
        const float difference =
            bilinearSample(views.planes[i * channels + c], ns, nt, x - uc * d, double(y) - vc * d) - reference[c];
        squares += difference * difference;
      }
      // The interpolation-bias term (depth.cpp's correspondenceCost).
      float bias = 0;
      if (views.locking > 0) {
        const double bx = interpolationBlur(-uc * d), by = interpolationBlur(-vc * d);
        bias = float(views.locking * (bx * bx * views.xx[p] + by * by * views.yy[p] + bx * by * views.xy[p]));
      }
      const float loss = float(referenceLoss + interpolationNoiseLoss(views.noise, -uc * d, -vc * d));
      for (std::size_t j = 0; j < subsets; ++j)
        if ((views.subsets[i] >> j) & 1) sums[j] += squares - bias + loss;
    }
    for (std::size_t j = 0; j < subsets; ++j) out[j][x] = sums[j] / views.viewsIn[j];
  }
}

}  // namespace lfcam::edof
