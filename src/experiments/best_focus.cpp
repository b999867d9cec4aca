// Section 6.1, step 2 of the processing: "vary the refocus depth until maximum output image
// sharpness is achieved", sharpness being the 75%-energy cutoff of the point source's photograph.
#include <cmath>

#include "experiments/experiment_support.hpp"
#include "lfcam/analysis/analysis.hpp"
#include "lfcam/render/synthetic_camera.hpp"

namespace lfcam::experiments {

Result<double> cutoffOf(const Image& photo) {
  LFCAM_ASSIGN_OR_RETURN(auto transfer, transferFunction(photo, kCutoffZeroPadding));
  return cutoffFrequency(transfer, 0.75);
}

namespace {

struct Focused {
  double slope = 0;
  double cutoff = -1;  // the search's measure, then the 75%-energy cutoff
  Image photo;
};

// The energy of the transfer function over |H(0)|^2 (Parseval: pixels x sum p^2 / (sum p)^2),
// how tightly the point's light is gathered. Unlike the cutoff it drops when the point is
// spread into ghost copies or speckle, so it finds the focus over the whole refocus range.
Result<double> concentrationOf(const Image& photo) {
  double sum = 0, squares = 0;
  for (float v : photo.pixels()) {
    sum += v;
    squares += double(v) * v;
  }
  if (!(sum > 0)) return makeError(ErrorCode::Usage, "best focus: the photograph sums to zero");
  return double(photo.planeSize()) * squares / (sum * sum);
}

// The slope of highest `measure` among `steps` slopes over centre +- halfWidth, then
// `levels - 1` times 21 around the best, each level 15 times finer.
Result<Focused> search(const LightField& lightField, const RenderOptions& method, double centre, double halfWidth,
                       int steps, int levels, Result<double> (*measure)(const Image&)) {
  Focused best;
  for (int level = 0; level < levels; ++level) {
    const int count = level == 0 ? steps : 21;
    for (int k = 0; k < count; ++k) {
      SyntheticCamera camera;
      camera.slope = centre - halfWidth + 2 * halfWidth * k / (count - 1);
      LFCAM_ASSIGN_OR_RETURN(auto photo, renderSyntheticPhoto(lightField, camera, method));
      LFCAM_ASSIGN_OR_RETURN(auto cutoff, measure(photo));
      if (cutoff > best.cutoff) best = {camera.slope, cutoff, std::move(photo)};
    }
    centre = best.slope;
    halfWidth *= 2.0 / (count - 1) * 1.5;
  }
  return best;
}

}  // namespace

Result<BestFocus> refocusToSharpest(const LightField& lightField) {
  // Every slope a view step can shift: up to the light field's own size in each direction.
  const double range = 0.5 * std::max(lightField.ns(), lightField.nt()) / std::max(1.0, 0.5 * lightField.nu());
  // The focus over the whole range by the concentration of the point (quadrature method: its
  // supersampled aperture spreads fewer ghosts): the cutoff alone is fooled far from focus by
  // ghost copies and Monte Carlo speckle, whose fine structure it counts as detail.
  const RenderOptions quadratureMethod{RenderMethod::Quadrature, 0}, viewsMethod{RenderMethod::Quadrature, 1};
  LFCAM_ASSIGN_OR_RETURN(auto coarse,
                         search(lightField, quadratureMethod, 0, std::min(range, 12.0), 61, 3, concentrationOf));
  // Then the paper's criterion, the highest cutoff, within +-0.5 pixel per view step of it: by the
  // quadrature method, and by the views alone (shift-and-add, one term per view), which line up
  // there and need no blending of neighbouring views, the quadrilinear filter's blur in u that
  // section 6.3 names among the paper's losses.
  LFCAM_ASSIGN_OR_RETURN(auto quadrature, search(lightField, quadratureMethod, coarse.slope, 0.5, 41, 2, cutoffOf));
  LFCAM_ASSIGN_OR_RETURN(auto views, search(lightField, viewsMethod, coarse.slope, 0.5, 41, 2, cutoffOf));
  return BestFocus{views.slope,      views.cutoff,      std::move(views.photo),
                   quadrature.slope, quadrature.cutoff, std::move(quadrature.photo)};
}

}  // namespace lfcam::experiments
