// From what a user asks for to the camera of synthetic_camera.hpp (photo_settings.hpp).
#include "lfcam/photo_settings.hpp"

#include <string>
#include <utility>

#include "lfcam/focal_stack.hpp"
#include "lfcam/fourier_slice.hpp"

namespace lfcam {

Result<PhotoSetup> photoSetup(const PhotoSettings& settings, const LightField& lightField,
                              const std::string& inputName) {
  PhotoSetup setup;
  setup.method = settings.method;
  const auto [u, v] = settings.apertureCentre.value_or(std::array<double, 2>{0, 0});
  Aperture& aperture = setup.camera.aperture;
  if (settings.apertureMask) {
    if (settings.apertureRadius)
      return makeError(ErrorCode::Usage, "an aperture radius and an aperture mask exclude each other");
    aperture = Aperture{Aperture::Shape::Mask, 0, u, v, settings.apertureMask};
  } else if (settings.apertureRadius) {
    aperture = settings.squareAperture ? Aperture::square(*settings.apertureRadius, u, v)
                                       : Aperture::circle(*settings.apertureRadius, u, v);
  } else if (settings.apertureCentre) {
    return makeError(ErrorCode::Usage, "an aperture centre needs an aperture radius or an aperture mask");
  }
  if (settings.beta && *settings.beta != 1) {
    const auto& optics = lightField.metadata.optics;
    if (!optics)
      return makeError(ErrorCode::Usage, inputName + ": no optics metadata, so the lens plane cannot be moved (beta)");
    setup.camera.beta = *settings.beta;
    setup.camera.parallax = optics->lensStepMm / optics->spatialStepMm;
  }
  if (settings.method == PhotoMethod::Fourier && (aperture.shape != Aperture::Shape::Full || setup.camera.beta != 1))
    return makeError(ErrorCode::Usage, "the Fourier method renders the full aperture at beta 1 only");
  setup.render.method = settings.method == PhotoMethod::Quadrature ? RenderMethod::Quadrature : RenderMethod::Fast;
  setup.render.supersampling = settings.supersampling;
  return setup;
}

Result<double> slopeFromAlpha(const LightField& lightField, double alpha, const std::string& inputName) {
  if (!(alpha > 0)) return makeError(ErrorCode::Usage, "alpha must be positive, got " + std::to_string(alpha));
  const auto& optics = lightField.metadata.optics;
  if (!optics)
    return makeError(ErrorCode::Usage, inputName +
                                           ": no optics metadata, so alpha cannot be converted to a slope; give the "
                                           "slope (pixels per view step)");
  return optics->slopeFromAlpha(alpha);
}

Status renderPhotos(const LightField& lightField, const PhotoSetup& setup, const std::vector<double>& slopes,
                    const std::function<Status(int index, double slope, Image&& photo)>& sink) {
  if (setup.method != PhotoMethod::Fourier)
    return renderFocalStack(lightField, slopes, setup.camera, setup.render, sink);
  LFCAM_ASSIGN_OR_RETURN(auto refocuser, FourierRefocuser::create(lightField));
  for (std::size_t i = 0; i < slopes.size(); ++i) LFCAM_TRY(sink(int(i), slopes[i], refocuser.refocus(slopes[i])));
  return {};
}

}  // namespace lfcam
