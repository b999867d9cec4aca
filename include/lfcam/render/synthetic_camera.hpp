// The synthetic camera of Equation 5 (section 4): a photograph taken inside the light field by a
// camera whose film plane (alpha), lens plane (beta) and aperture A(u', v') differ from the real
// camera's. Refocusing (Equation 6, beta = 1) and moving the observer (Equation 7, alpha = 1,
// a pinhole aperture) are its special cases.
//
// Geometry (../shared/docs/paper-notes.md, with F = 1): the lens plane is at z = 0, the
// microlens plane at z = 1, the synthetic film at z = alpha and the synthetic lens at
// z = 1 - beta. A ray through u' (synthetic lens) and s' (synthetic film) crosses
//   the lens plane at      u = s' + (u' - s') alpha / (alpha + beta - 1)
//   the microlens plane at s = u' + (s' - u') beta  / (alpha + beta - 1).
// Output pixels are counted on the microlens plane (s' = alpha * sigma, the film photograph
// scaled back by its magnification, as refocus.hpp and the HCI convention do), around the
// optical axis at the image centre. In the units of light_field.hpp ((u, v) view steps from the
// centre, (s, t) pixels, r = du/ds pixels per view step) and its sign convention this is, with
// a = alpha/(alpha+beta-1), b = beta/(alpha+beta-1) and sigma measured from the image centre:
//   u = a u' - alpha (1 - a) sigma / r
//   s = centre + alpha b sigma - r (1 - b) u'
// For beta = 1: u = u', s = sigma - u' slope with slope = r (1 - 1/alpha) (Equation 6).
// For alpha = 1: s = sigma, u = u'/beta - (1 - 1/beta) sigma / r (Equation 7).
//
// The film plane is given as the slope it brings into focus (Optics::slopeFromAlpha converts an
// alpha), so that light fields without optics can be refocused; beta != 1 needs r
// (Optics::lensStepMm / Optics::spatialStepMm), which light fields without optics do not carry.
//
// Every photograph is normalised by the weight of the rays that actually contributed (aperture
// weight x light field weight x interpolation coefficient of each tap inside the light field,
// section 5.2): its brightness does not depend on the aperture's size or on vignetting, and a
// pixel no ray reaches is 0.
#pragma once

#include <memory>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

// A(u', v'): the synthetic aperture on the synthetic lens plane, in view steps from the centre
// of the aperture (the same units as the views: a view covers a unit square around its
// position).
struct Aperture {
  enum class Shape { Full, Circle, Square, Mask };
  Shape shape = Shape::Full;
  double radius = 0;                // Circle: radius; Square: half its side; view steps. 0: one view
  double centreU = 0, centreV = 0;  // where the aperture is centred, view steps from the centre
  // Mask: an image laid over the whole lens, [-nu/2, nu/2] x [-nv/2, nv/2] view steps (x with u,
  // y with v), moved by the centre; A is the mean of its channels clamped to [0, 1], sampled at
  // the nearest pixel, and 0 outside it.
  std::shared_ptr<const Image> mask;

  static Aperture full() { return {}; }
  static Aperture circle(double radius, double u = 0, double v = 0) { return {Shape::Circle, radius, u, v, {}}; }
  static Aperture square(double halfSide, double u = 0, double v = 0) { return {Shape::Square, halfSide, u, v, {}}; }
  static Aperture fromMask(Image mask, double u = 0, double v = 0) {
    return {Shape::Mask, 0, u, v, std::make_shared<const Image>(std::move(mask))};
  }

  // A at lens position (u, v), view steps from the centre, of a light field with nu x nv views.
  // Points on the edge of a circle or square are inside.
  double weight(double u, double v, int nu, int nv) const;
};

struct SyntheticCamera {
  double slope = 0;     // film plane: the disparity it brings into focus (alpha via Optics)
  double beta = 1;      // synthetic lens plane, at distance beta F from the microlens plane
  double parallax = 0;  // r = du/ds, pixels per view step; needed only when beta != 1
  Aperture aperture;
};

enum class RenderMethod {
  Fast,        // one term per view: the aperture sampled at the views (shift-and-add for beta = 1)
  Quadrature,  // section 5.2: the aperture supersampled between the views with a quadrilinear
               // reconstruction filter, for large refocus distances (no ghost copies)
};

struct RenderOptions {
  RenderMethod method = RenderMethod::Fast;
  // Quadrature: aperture samples per view step on each axis; 0 picks ceil(|slope|) in [1, 8]
  // (so that adjacent samples shift the image by at most a pixel).
  int supersampling = 0;
};

// The photograph of `camera`. Usage errors: beta != 1 without a parallax, a degenerate camera
// (alpha + beta = 1, film and lens on one plane), an aperture that selects no ray of the
// light field. The Fast method with beta = 1 and a full aperture is exactly refocus(slope).
// Cost: Fast with beta = 1 streams each view once (refocus.hpp); Quadrature about
// 4 supersampling^2 times that; beta != 1 interpolates 16 taps per ray, per pixel.
Result<Image> renderSyntheticPhoto(const LightField& lightField, const SyntheticCamera& camera,
                                   const RenderOptions& options = {});

// Moving the observer (Equation 7, Figures 6, 7 and 18): a pinhole at (u, v) view steps from
// the centre of the lens plane, moved along the axis by beta, film at the real film plane
// (alpha = 1). Each pixel takes the one ray through the pinhole, interpolated quadrilinearly.
// Rays that leave the lens are vignetted (their taps carry no weight; a pixel with none is 0),
// or with clampToLens replaced by the closest available ray (Figure 7: the lens position clamped
// to the outermost views), which gives a multi-perspective image without black.
struct Observer {
  double u = 0, v = 0;
  double beta = 1;
  double parallax = 0;  // r = du/ds, needed when beta != 1
  bool clampToLens = false;
};
Result<Image> observe(const LightField& lightField, const Observer& observer);

}  // namespace lfcam
