// PhotoSettings: a synthetic photograph as a user asks for it (the aperture by radius, shape and
// centre or by a mask, the lens plane, the method), turned into the SyntheticCamera and
// RenderOptions of synthetic_camera.hpp for one light field, and the photographs rendered for a
// list of slopes. The command line (`refocus`, `stack`) and the Python package both go through
// it, so they accept and refuse the same requests with the same messages.
//
// Units as in light_field.hpp: radius and centre in view steps from the aperture centre, slopes in
// pixels per view step. Usage errors: a radius and a mask together, a centre with neither, beta or
// alpha without optics metadata, the Fourier method with anything but the full aperture at beta 1.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/image.hpp"
#include "lfcam/light_field.hpp"
#include "lfcam/result.hpp"
#include "lfcam/synthetic_camera.hpp"

namespace lfcam {

enum class PhotoMethod {
  Fast,        // shift-and-add of the views (RenderMethod::Fast)
  Quadrature,  // the aperture supersampled between views (RenderMethod::Quadrature)
  Fourier,     // Fourier slice refocusing: one 4D FFT, then each photograph from a 2D slice
};

struct PhotoSettings {
  std::optional<double> apertureRadius;                 // none: the whole lens; 0: one view
  bool squareAperture = false;                          // a square of half side apertureRadius
  std::optional<std::array<double, 2>> apertureCentre;  // (u, v)
  std::shared_ptr<const Image> apertureMask;            // Aperture::Shape::Mask
  PhotoMethod method = PhotoMethod::Fast;
  int supersampling = 0;       // Quadrature: 0 picks one (synthetic_camera.hpp)
  std::optional<double> beta;  // relative position of the synthetic lens plane; needs optics
};

struct PhotoSetup {
  SyntheticCamera camera;  // slope left at 0: each photograph sets its own
  RenderOptions render;
  PhotoMethod method = PhotoMethod::Fast;
};

// The camera `settings` describe for `lightField`; `inputName` starts messages about its metadata.
Result<PhotoSetup> photoSetup(const PhotoSettings& settings, const LightField& lightField,
                              const std::string& inputName);

// The slope of the relative film depth alpha (Equation 6) for this light field's optics.
Result<double> slopeFromAlpha(const LightField& lightField, double alpha, const std::string& inputName);

// One photograph per slope, handed to `sink` in order as it is made (renderFocalStack, or the
// Fourier slice method with its spectrum computed once). Stops at the first error.
Status renderPhotos(const LightField& lightField, const PhotoSetup& setup, const std::vector<double>& slopes,
                    const std::function<Status(int index, double slope, Image&& photo)>& sink);

}  // namespace lfcam
