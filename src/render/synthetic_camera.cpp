// The synthetic camera (Equation 5) and the moving observer (Equation 7): synthetic_camera.hpp.
//
// Three ways to evaluate the same integral:
//   - beta = 1: every ray of one aperture sample hits the lens plane at the same u, so each
//     sample is one view (or a bilinear blend of four, between views) shifted by a constant:
//     the shift-and-add kernel of refocus.cpp (shift_and_add.hpp), fast.
//   - beta != 1: u varies across the image, so each ray is interpolated quadrilinearly in
//     (u, v, s, t), per output pixel: renderRays (ray_paths.hpp), in float32 and threaded.
//   - the reference: renderRays in float64, single-threaded, for every case.
#include "lfcam/render/synthetic_camera.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lfcam/render/refocus.hpp"
#include "render/ray_paths.hpp"
#include "render/references.hpp"

namespace lfcam {

double Aperture::weight(double u, double v, int nu, int nv) const {
  const double du = u - centreU, dv = v - centreV;
  const double tolerance = 1e-9;  // views exactly on the edge are inside
  switch (shape) {
    case Shape::Full: return 1;
    case Shape::Circle: return du * du + dv * dv <= radius * radius + tolerance ? 1 : 0;
    case Shape::Square: return std::abs(du) <= radius + tolerance && std::abs(dv) <= radius + tolerance ? 1 : 0;
    case Shape::Mask: {
      if (!mask || mask->empty() || nu <= 0 || nv <= 0) return 0;
      const double x = (du / nu + 0.5) * mask->width(), y = (dv / nv + 0.5) * mask->height();
      if (!(x >= 0 && y >= 0 && x < mask->width() && y < mask->height())) return 0;
      double sum = 0;
      for (int c = 0; c < mask->channels(); ++c) sum += mask->at(int(x), int(y), c);
      return std::clamp(sum / mask->channels(), 0.0, 1.0);
    }
  }
  return 0;
}

namespace {

int supersamplingFor(const SyntheticCamera& camera, const RenderOptions& options) {
  if (options.method == RenderMethod::Fast) return 1;
  if (options.supersampling > 0) return options.supersampling;
  return std::clamp(int(std::ceil(std::abs(camera.slope))), 1, 8);
}

Status checkInput(const LightField& lightField, const std::vector<ApertureSample>& samples) {
  if (lightField.empty()) return makeError(ErrorCode::Usage, "synthetic camera: empty light field");
  if (samples.empty())
    return makeError(ErrorCode::Usage, "synthetic camera: the aperture lets no ray of the light field through");
  return {};
}

}  // namespace

Result<Image> renderSyntheticPhoto(const LightField& lightField, const SyntheticCamera& camera,
                                   const RenderOptions& options) {
  LFCAM_TRY(rayMap(camera.slope, camera.beta, camera.parallax));  // a degenerate camera is an error, not a black photo
  const int supersampling = supersamplingFor(camera, options);
  const std::vector<ApertureSample> samples = apertureSamples(lightField, camera.aperture, supersampling);
  LFCAM_TRY(checkInput(lightField, samples));
  if (camera.beta == 1) {
    // The full aperture at the views is the plain refocus, with its separable normalisation.
    if (camera.aperture.shape == Aperture::Shape::Full && supersampling == 1) return refocus(lightField, camera.slope);
    return renderShiftAndAdd(lightField, camera.slope, samples);
  }
  return renderRays<float>(lightField, {.plane = {.slope = camera.slope}}, samples,
                           {.beta = camera.beta, .parallax = camera.parallax});
}

Result<Image> renderSyntheticPhotoReference(const LightField& lightField, const SyntheticCamera& camera,
                                            int supersampling) {
  LFCAM_TRY(rayMap(camera.slope, camera.beta, camera.parallax));  // a degenerate camera is an error, not a black photo
  const std::vector<ApertureSample> samples = apertureSamples(lightField, camera.aperture, supersampling);
  LFCAM_TRY(checkInput(lightField, samples));
  return renderRays<double>(lightField, {.plane = {.slope = camera.slope}}, samples,
                            {.beta = camera.beta, .parallax = camera.parallax});
}

namespace {

Result<Image> observeWith(const LightField& lightField, const Observer& observer, bool reference) {
  if (lightField.empty()) return makeError(ErrorCode::Usage, "observer: empty light field");
  if (!std::isfinite(observer.u) || !std::isfinite(observer.v))
    return makeError(ErrorCode::Usage, "observer: the position must be finite");
  // alpha = 1: the real film plane.
  LFCAM_TRY(rayMap(0.0, observer.beta, observer.parallax));
  const std::vector<ApertureSample> pinhole{{observer.u, observer.v, 1.0}};
  const RayOptions options{.beta = observer.beta, .parallax = observer.parallax, .clampToLens = observer.clampToLens};
  if (reference) return renderRays<double>(lightField, {}, pinhole, options);
  if (observer.beta == 1) {
    // On the real lens plane the pinhole's ray lands on the same (u, v) for every pixel: a blend
    // of the (at most) four views around it, at no shift, which the shift-and-add kernel streams
    // (clamping moves the pinhole itself onto the lens). Measured by lfcam bench's observer.
    ApertureSample sample = pinhole.front();
    if (observer.clampToLens) {
      sample.u = std::clamp(sample.u, lightField.uFromCentre(0), lightField.uFromCentre(lightField.nu() - 1));
      sample.v = std::clamp(sample.v, lightField.vFromCentre(0), lightField.vFromCentre(lightField.nv() - 1));
    }
    return renderShiftAndAdd(lightField, 0.0, {sample});
  }
  return renderRays<float>(lightField, {}, pinhole, options);
}

}  // namespace

Result<Image> observe(const LightField& lightField, const Observer& observer) {
  return observeWith(lightField, observer, false);
}

Result<Image> observeReference(const LightField& lightField, const Observer& observer) {
  return observeWith(lightField, observer, true);
}

}  // namespace lfcam
