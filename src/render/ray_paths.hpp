// The general path of Equation 5 (synthetic_camera.hpp's geometry), per output pixel: each aperture
// sample's ray through the pixel, at the pixel's own film slope, interpolated quadrilinearly in
// (u, v, s, t) and weighted by A x the light field's weight x the interpolation coefficients, then
// normalised. It renders every photograph a PhotoRequest can describe (photo_request.hpp), on the
// views' grid or a finer one; the fast kernels cover its common cases, and its float64 instance is
// their oracle. Internal to the library.
#pragma once

#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/render/synthetic_camera.hpp"
#include "lfcam/render/tilted_focus.hpp"
#include "render/occluders.hpp"

namespace lfcam {

// One sample of the aperture: a position on the synthetic lens plane and its weight A.
struct ApertureSample {
  double u = 0, v = 0;  // view steps from the centre
  double weight = 0;
};

// supersampling^2 samples per view, at the centres of a regular grid over each view's square
// (supersampling 1: the views themselves); samples of weight 0 are dropped.
std::vector<ApertureSample> apertureSamples(const LightField& lightField, const Aperture& aperture, int supersampling);

// The linear map of synthetic_camera.hpp from (aperture sample, output pixel) to the ray's
// coordinates in the light field, per axis: lens = uu * u' + us * sigma, spatial = su * u' + ss * sigma
// (from the centres). Usage errors: non-finite values, beta != 1 without a parallax, a film plane
// at infinity or on the lens plane.
struct RayMap {
  double uu = 1, us = 0, su = 0, ss = 1;
};
Result<RayMap> rayMap(double slope, double beta, double parallax);

// The film's slope at each output pixel: a plane in (x, y, slope), or each pixel's own disparity
// clamped into [farSlope, nearSlope] (a focus range, focus_spread.hpp).
struct FilmSlopes {
  FocusPlane plane;
  const Image* depth = nullptr;
  double farSlope = 0, nearSlope = 0;
  // At view pixel (x, y) (indices), for the image point (px, py) inside it.
  double at(int x, int y, double px, double py) const;
};

struct RayOptions {
  double beta = 1, parallax = 0;
  bool clampToLens = false;              // rays off the lens take the nearest lens position
  int factor = 1;                        // output pixels per view pixel, on each axis
  const Occluders* occluders = nullptr;  // with a range: leave out the rays nearer surfaces hide
};

// The photograph: (factor ns) x (factor nt) pixels. A pixel whose ray map is degenerate (its film
// at infinity or on the lens plane) or which no ray reaches is 0. Real = double single-threaded:
// the reference; float: threaded over rows.
template <class Real>
Image renderRays(const LightField& lightField, const FilmSlopes& film, const std::vector<ApertureSample>& samples,
                 const RayOptions& options);

// beta = 1 and a flat film: each aperture sample is the view at its lens position (a bilinear blend
// of the four around it between views), shifted by -(u', v') slope: the shift-and-add kernel.
Image renderShiftAndAdd(const LightField& lightField, double slope, const std::vector<ApertureSample>& samples);

}  // namespace lfcam
