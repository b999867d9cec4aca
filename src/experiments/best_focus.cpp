// Section 6.1, step 2 of the processing: "vary the refocus depth until maximum output image
// sharpness is achieved", sharpness being the 75%-energy cutoff of the point source's photograph.
#include <cmath>

#include "experiments/experiment_support.hpp"
#include "lfcam/analysis.hpp"
#include "lfcam/synthetic_camera.hpp"

namespace lfcam::experiments {

Result<double> cutoffOf(const Image& photo) {
  auto transfer = transferFunction(photo);
  if (!transfer) return transfer.error();
  return cutoffFrequency(*transfer, 0.75);
}

Result<BestFocus> refocusToSharpest(const LightField& lightField) {
  // Every slope a view step can shift: up to the light field's own size in each direction.
  const double range = 0.5 * std::max(lightField.ns(), lightField.nt()) / std::max(1.0, 0.5 * lightField.nu());
  auto render = [&](double slope) -> Result<BestFocus> {
    SyntheticCamera camera;
    camera.slope = slope;
    auto photo = renderSyntheticPhoto(lightField, camera, RenderOptions{RenderMethod::Quadrature, 0});
    if (!photo) return photo.error();
    auto cutoff = cutoffOf(*photo);
    if (!cutoff) return cutoff.error();
    return BestFocus{slope, *cutoff, std::move(*photo)};
  };
  double centre = 0, halfWidth = std::min(range, 12.0);
  BestFocus best;
  best.cutoff = -1;
  // Coarse to fine: 61 slopes over the range, then twice 21 around the best.
  for (int level = 0; level < 3; ++level) {
    const int steps = level == 0 ? 61 : 21;
    for (int k = 0; k < steps; ++k) {
      const double slope = centre - halfWidth + 2 * halfWidth * k / (steps - 1);
      auto candidate = render(slope);
      if (!candidate) return candidate.error();
      if (candidate->cutoff > best.cutoff) best = std::move(*candidate);
    }
    centre = best.slope;
    halfWidth *= 2.0 / (steps - 1) * 1.5;
  }
  return best;
}

}  // namespace lfcam::experiments
