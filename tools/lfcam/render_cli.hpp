// Options shared by the rendering subcommands (refocus, stack): the synthetic aperture, the lens
// plane and the method, and the small value parsers they need. Values on the command line are in
// view steps from the centre view (u, v, R) and pixels per view step (slopes).
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lfcam/focal_stack.hpp"
#include "lfcam/image_io.hpp"
#include "lfcam/light_field.hpp"
#include "lfcam/photo_settings.hpp"
#include "lfcam/result.hpp"
#include "lfcam/tilted_focus.hpp"

namespace lfcam::cli {

// "X,Y" -> two finite numbers.
inline Result<std::pair<double, double>> parsePair(const std::string& text, const std::string& option) {
  double a = 0, b = 0;
  char end = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf%c", &a, &b, &end) != 2 || !std::isfinite(a) || !std::isfinite(b))
    return makeError(ErrorCode::Usage, option + ": expected two numbers as X,Y, got '" + text + "'");
  return std::pair{a, b};
}

struct CameraOptions {
  std::optional<double> radius;
  std::string shape = "circle";
  std::string centre;
  std::string mask;
  std::string method = "fast";
  int supersampling = 0;
  std::optional<double> beta;
  // The plain photograph: the whole lens, the fast method, the lens plane where it was.
  bool isFullApertureFast() const {
    return !radius && shape == "circle" && centre.empty() && mask.empty() && method == "fast" && supersampling == 0 &&
           !beta;
  }
};

inline void addCameraOptions(CLI::App& command, CameraOptions& options) {
  command
      .add_option("--aperture", options.radius,
                  "synthetic aperture radius in view steps (0: one view; default: the whole lens)")
      ->check(CLI::NonNegativeNumber);
  command.add_option("--aperture-shape", options.shape, "circle or square (half side = R)")
      ->check(CLI::IsMember({"circle", "square"}));
  // --aperture-center: the spelling of earlier versions, still accepted.
  command.add_option("--aperture-centre,--aperture-center", options.centre,
                     "aperture centre U,V in view steps from the centre view");
  command.add_option("--aperture-mask", options.mask,
                     "image laid over the whole lens whose brightness weights each view (white: full weight)");
  command
      .add_option("--method", options.method,
                  "fast (shift-and-add of the views), quadrature (aperture supersampled, for large "
                  "refocus distances) or fourier (Fourier slice: one 4D FFT, then fast per photo; full "
                  "aperture only)")
      ->check(CLI::IsMember({"fast", "quadrature", "fourier"}));
  command
      .add_option("--supersampling", options.supersampling,
                  "quadrature: aperture samples per view step (default: about |slope|)")
      ->check(CLI::Range(1, 32));
  command.add_option("--beta", options.beta, "relative position of the synthetic lens plane (needs optics)")
      ->check(CLI::PositiveNumber);
}

// The photograph the flags describe, for this light field (slope left at 0).
inline Result<PhotoSetup> cameraFrom(const CameraOptions& options, const LightField& lightField,
                                     const std::string& inputName) {
  PhotoSettings settings;
  if (!options.centre.empty()) {
    LFCAM_ASSIGN_OR_RETURN(auto centre, parsePair(options.centre, "--aperture-centre"));
    settings.apertureCentre = std::array<double, 2>{centre.first, centre.second};
  }
  if (!options.mask.empty()) {
    LFCAM_ASSIGN_OR_RETURN(auto mask, readImage(options.mask));
    settings.apertureMask = std::make_shared<const Image>(std::move(mask));
  }
  settings.apertureRadius = options.radius;
  settings.squareAperture = options.shape == "square";
  settings.method = options.method == "quadrature" ? PhotoMethod::Quadrature
                    : options.method == "fourier"  ? PhotoMethod::Fourier
                                                   : PhotoMethod::Fast;
  settings.supersampling = options.supersampling;
  settings.beta = options.beta;
  return photoSetup(settings, lightField, inputName);
}

}  // namespace lfcam::cli
