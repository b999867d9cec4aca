// renderPhoto (photo_request.hpp): which kernel renders a resolved photograph, and its oracle.
//
//   a flat film (one slope), beta 1           renderSyntheticPhoto: refocus, or shift-and-add of
//                                             the aperture's samples (a pinhole: observe's blend)
//   a tilted or ranged film, fast, beta 1     the slope-field kernel, the aperture's weight per view
//   on a finer grid, flat, whole lens, fast   the splat of upsampled_refocus.hpp (detail finer than
//                                             the microlenses)
//   fourier                                   the Fourier slice refocuser
//   everything else (beta != 1, quadrature   the general path: every ray per output pixel
//   or a pinhole with a film that is not      (ray_paths.hpp), on the views' grid or a finer one
//   flat, clamping, a finer grid otherwise)
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "lfcam/photo/photo_request.hpp"
#include "lfcam/render/fourier_slice.hpp"
#include "lfcam/render/upsampled_refocus.hpp"
#include "render/occluders.hpp"
#include "render/ray_paths.hpp"
#include "render/references.hpp"
#include "render/slope_field_rows.hpp"

namespace lfcam {

namespace {

bool isFlat(const ResolvedFilm& film) { return !film.depth && film.plane.gradientX == 0 && film.plane.gradientY == 0; }

bool wholeLens(const ResolvedPhoto& photo) { return photo.aperture.shape == Aperture::Shape::Full; }

int supersamplingOf(const ResolvedPhoto& photo) {
  if (photo.method != PhotoMethod::Quadrature) return 1;
  if (photo.supersampling > 0) return photo.supersampling;
  // Adjacent samples shift the image by at most a pixel at the steepest slope the film has.
  double steepest = std::abs(photo.film.plane.slope);
  if (photo.film.range) steepest = std::max(std::abs((*photo.film.range)[0]), std::abs((*photo.film.range)[1]));
  return std::clamp(int(std::ceil(steepest)), 1, 8);
}

// The aperture's samples: one at its centre for a pinhole (clamped onto the lens's views when
// asked), else supersampling^2 per view.
std::vector<ApertureSample> samplesOf(const LightField& lightField, const ResolvedPhoto& photo) {
  if (!photo.pinhole) return apertureSamples(lightField, photo.aperture, supersamplingOf(photo));
  ApertureSample sample{photo.aperture.centreU, photo.aperture.centreV, 1.0};
  if (photo.clamp && photo.beta == 1) {
    sample.u = std::clamp(sample.u, lightField.uFromCentre(0), lightField.uFromCentre(lightField.nu() - 1));
    sample.v = std::clamp(sample.v, lightField.vFromCentre(0), lightField.vFromCentre(lightField.nv() - 1));
  }
  return {sample};
}

FilmSlopes filmSlopes(const ResolvedFilm& film) {
  FilmSlopes slopes{.plane = film.plane};
  if (film.depth) {
    slopes.depth = film.depth.get();
    slopes.farSlope = (*film.range)[0];
    slopes.nearSlope = (*film.range)[1];
  }
  return slopes;
}

Status checkSamples(const std::vector<ApertureSample>& samples) {
  if (samples.empty()) return makeError(ErrorCode::Usage, "the aperture lets no ray of the light field through");
  return {};
}

// The general path, float32 or float64.
template <class Real>
Result<Image> renderGeneral(const LightField& lightField, const ResolvedPhoto& photo) {
  const std::vector<ApertureSample> samples = samplesOf(lightField, photo);
  LFCAM_TRY(checkSamples(samples));
  std::optional<Occluders> occluders;
  if (photo.film.depth) occluders.emplace(lightField, *photo.film.depth);
  return renderRays<Real>(lightField, filmSlopes(photo.film), samples,
                          {.beta = photo.beta,
                           .parallax = photo.parallax,
                           .clampToLens = photo.clamp,
                           .factor = photo.upsample,
                           .occluders = occluders ? &*occluders : nullptr});
}

bool plainUpsample(const ResolvedPhoto& photo) {
  return photo.upsample > 1 && isFlat(photo.film) && wholeLens(photo) && photo.beta == 1 &&
         photo.method == PhotoMethod::Fast;
}

}  // namespace

Result<Image> renderPhoto(const LightField& lightField, const ResolvedPhoto& photo) {
  if (photo.method == PhotoMethod::Fourier) {
    LFCAM_ASSIGN_OR_RETURN(auto refocuser, FourierRefocuser::create(lightField));
    return refocuser.refocus(photo.film.plane.slope);
  }
  if (plainUpsample(photo)) return refocusUpsampled(lightField, photo.film.plane.slope, photo.upsample);
  // At beta 1 the fast method's samples sit on the views, so only a pinhole's ray (clamped in
  // samplesOf) or quadrature's samples can leave the lens.
  const bool clampBetweenViews = photo.clamp && photo.method == PhotoMethod::Quadrature;
  if (photo.upsample == 1 && photo.beta == 1 && !clampBetweenViews) {
    if (isFlat(photo.film)) {
      if (photo.pinhole) return renderShiftAndAdd(lightField, photo.film.plane.slope, samplesOf(lightField, photo));
      return renderSyntheticPhoto(
          lightField, {.slope = photo.film.plane.slope, .aperture = photo.aperture},
          {photo.method == PhotoMethod::Quadrature ? RenderMethod::Quadrature : RenderMethod::Fast,
           photo.supersampling});
    }
    if (photo.method == PhotoMethod::Fast && !photo.pinhole) {
      std::vector<float> weights;
      if (!wholeLens(photo)) {
        for (const ApertureSample& sample : apertureSamples(lightField, Aperture::full(), 1))
          weights.push_back(float(photo.aperture.weight(sample.u, sample.v, lightField.nu(), lightField.nv())));
        if (std::all_of(weights.begin(), weights.end(), [](float w) { return w == 0; }))
          return checkSamples({}).error();
      }
      std::optional<Occluders> occluders;
      if (photo.film.depth) occluders.emplace(lightField, *photo.film.depth);
      return refocusFilm(lightField, filmSlopes(photo.film), occluders ? &*occluders : nullptr,
                         weights.empty() ? nullptr : &weights);
    }
  }
  return renderGeneral<float>(lightField, photo);
}

Result<Image> renderPhoto(const LightField& lightField, const PhotoRequest& request, const ResolveOptions& options) {
  LFCAM_ASSIGN_OR_RETURN(auto photo, resolvePhoto(request, lightField, options));
  return renderPhoto(lightField, photo);
}

Result<Image> renderPhotoReference(const LightField& lightField, const ResolvedPhoto& photo) {
  if (plainUpsample(photo)) return refocusUpsampledReference(lightField, photo.film.plane.slope, photo.upsample);
  return renderGeneral<double>(lightField, photo);
}

Status renderPhotos(const LightField& lightField, const ResolvedPhoto& photo, const std::vector<double>& slopes,
                    const std::function<Status(int index, double slope, Image&& photo)>& sink) {
  if (!isFlat(photo.film))
    return makeError(ErrorCode::Usage,
                     "a focal stack is a series of flat focuses: no tilt, focus-plane or focus-range");
  if (photo.method == PhotoMethod::Fourier) {
    LFCAM_ASSIGN_OR_RETURN(auto refocuser, FourierRefocuser::create(lightField));
    for (std::size_t i = 0; i < slopes.size(); ++i) LFCAM_TRY(sink(int(i), slopes[i], refocuser.refocus(slopes[i])));
    return {};
  }
  ResolvedPhoto slice = photo;
  for (std::size_t i = 0; i < slopes.size(); ++i) {
    slice.film.plane.slope = slopes[i];
    LFCAM_ASSIGN_OR_RETURN(auto image, renderPhoto(lightField, slice));
    LFCAM_TRY(sink(int(i), slopes[i], std::move(image)));
  }
  return {};
}

}  // namespace lfcam
