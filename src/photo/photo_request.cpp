// The photograph request (photo_request.hpp): its fields as every front end names them, the checks
// that need no light field, and its resolution against one light field.
#include "lfcam/photo/photo_request.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "lfcam/edof/depth.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/render/focus_spread.hpp"
#include "lfcam/render/upsampled_refocus.hpp"
#include "render/ray_paths.hpp"

namespace lfcam {

namespace {

Error usage(const std::string& message) { return makeError(ErrorCode::Usage, message); }

// The text, cut so that a hostile one cannot make the message long.
std::string quoted(const std::string& text) { return "'" + text.substr(0, 60) + (text.size() > 60 ? "...'" : "'"); }

Result<double> number(const char* name, const std::string& text) {
  double value = 0;
  char end = 0;
  if (std::sscanf(text.c_str(), "%lf%c", &value, &end) != 1 || !std::isfinite(value))
    return usage(std::string(name) + ": expected a number, got " + quoted(text));
  return value;
}

Result<int> whole(const char* name, const std::string& text) {
  int value = 0;
  char end = 0;
  if (std::sscanf(text.c_str(), "%d%c", &value, &end) != 1)
    return usage(std::string(name) + ": expected a whole number, got " + quoted(text));
  return value;
}

Result<std::array<double, 2>> pair(const char* name, const std::string& text) {
  double a = 0, b = 0;
  char end = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf%c", &a, &b, &end) != 2 || !std::isfinite(a) || !std::isfinite(b))
    return usage(std::string(name) + ": expected two numbers as X,Y, got " + quoted(text));
  return std::array<double, 2>{a, b};
}

// "NEAR:FAR" in slopes, or "NEARmm:FARmm".
Result<FocusRange> range(const std::string& text) {
  const auto colon = text.find(':');
  const Error bad = usage("focus-range: expected NEAR:FAR as slopes or as distances NEARmm:FARmm, got " + quoted(text));
  if (colon == std::string::npos) return bad;
  std::string ends[2] = {text.substr(0, colon), text.substr(colon + 1)};
  bool millimetres[2] = {false, false};
  double values[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    if (ends[i].size() > 2 && ends[i].compare(ends[i].size() - 2, 2, "mm") == 0) {
      millimetres[i] = true;
      ends[i].resize(ends[i].size() - 2);
    }
    char end = 0;
    if (std::sscanf(ends[i].c_str(), "%lf%c", &values[i], &end) != 1 || !std::isfinite(values[i])) return bad;
  }
  if (millimetres[0] != millimetres[1]) return bad;
  return FocusRange{values[0], values[1], millimetres[0]};
}

Result<bool> flag(const char* name, const std::string& text) {
  if (text.empty() || text == "1" || text == "true") return true;
  if (text == "0" || text == "false") return false;
  return usage(std::string(name) + ": expected true or false, got " + quoted(text));
}

Result<std::shared_ptr<const Image>> imageFile(const std::string& text) {
  LFCAM_ASSIGN_OR_RETURN(auto image, readImage(text));
  return std::make_shared<const Image>(std::move(image));
}

// Each parser sets one field; LFCAM_ASSIGN_OR_RETURN needs a function body, hence the lambdas.
#define LFCAM_FIELD(expr, member)                          \
  [](PhotoRequest& r, const std::string& text) -> Status { \
    LFCAM_ASSIGN_OR_RETURN(r.member, expr);                \
    return {};                                             \
  }

}  // namespace

std::span<const PhotoField> photoFields() {
  static const std::array<PhotoField, 18> fields{{
      {"slope", "focus", "D", "the disparity brought into focus, pixels per view step (HCI convention)", false,
       LFCAM_FIELD(number("slope", text), slope)},
      {"alpha", "focus", "A", "relative depth of the synthetic film plane (Equation 6; needs optics)", false,
       LFCAM_FIELD(number("alpha", text), alpha)},
      {"focus-at", "focus", "X,Y", "focus where image point X,Y (pixels) is sharpest", false,
       LFCAM_FIELD(pair("focus-at", text), focusAt)},
      {"focus-plane", "focus", "X1,Y1:X2,Y2:X3,Y3",
       "focus on the tilted plane through three image points (pixels), each at its sharpest", false,
       [](PhotoRequest& r, const std::string& text) -> Status {
         auto points = parseFocusPlanePoints(text);
         if (!points) return usage("focus-plane: " + points.error().message);
         r.focusPlane = *points;
         return {};
       }},
      {"tilt", "focus", "T",
       "tilt the plane of focus of slope, alpha or focus-at: the change of slope over one image width", false,
       LFCAM_FIELD(number("tilt", text), tilt)},
      {"tilt-direction", "focus", "DEG", "direction in which a tilted focus's slope grows (0: right, 90: down)", false,
       LFCAM_FIELD(number("tilt-direction", text), tiltDirection)},
      {"focus-range", "focus", "NEAR:FAR",
       "everything between two depths in focus: slopes (the near end the larger) or NEARmm:FARmm from the main "
       "lens (needs optics); the blur beyond grows as a lens focused at the range's end blurs it",
       false, LFCAM_FIELD(range(text), focusRange)},
      {"depth", "focus", "FILE",
       "with focus-range: the disparity map of the centre view, as lfcam depth writes it (default: estimated)", true,
       LFCAM_FIELD(imageFile(text), depth)},
      {"aperture", "aperture", "R", "aperture radius in view steps (0: a pinhole; default: the whole lens)", false,
       LFCAM_FIELD(number("aperture", text), aperture)},
      {"f-number", "aperture", "N",
       "aperture as an f-number relative to the whole lens (1: all of it; 2: half its radius)", false,
       LFCAM_FIELD(number("f-number", text), fNumber)},
      {"aperture-shape", "aperture", "SHAPE", "circle or square (half side = the radius)", false,
       [](PhotoRequest& r, const std::string& text) -> Status {
         if (text != "circle" && text != "square")
           return usage("aperture-shape: expected circle or square, got " + quoted(text));
         r.apertureShape = text;
         return {};
       }},
      {"aperture-centre", "aperture", "U,V",
       "aperture centre in view steps from the lens centre: where the observer stands (Equation 7)", false,
       LFCAM_FIELD(pair("aperture-centre", text), apertureCentre)},
      {"aperture-mask", "aperture", "FILE",
       "image laid over the whole lens whose brightness weights each ray (white: full weight)", true,
       LFCAM_FIELD(imageFile(text), apertureMask)},
      {"clamp", "aperture", "",
       "a ray that leaves the lens takes the outermost view's (Figure 7: no black where the observer moves off it)",
       false, LFCAM_FIELD(flag("clamp", text), clamp)},
      {"beta", "lens", "B", "relative position of the synthetic lens plane (Equation 5; needs optics)", false,
       LFCAM_FIELD(number("beta", text), beta)},
      {"method", "sampling", "METHOD",
       "fast (the aperture at the views), quadrature (supersampled between them: no ghosts far from focus) or "
       "fourier (Fourier slice: one 4D FFT; a flat focus through the whole lens only)",
       false,
       [](PhotoRequest& r, const std::string& text) -> Status {
         if (text == "fast")
           r.method = PhotoMethod::Fast;
         else if (text == "quadrature")
           r.method = PhotoMethod::Quadrature;
         else if (text == "fourier")
           r.method = PhotoMethod::Fourier;
         else
           return usage("method: expected fast, quadrature or fourier, got " + quoted(text));
         return {};
       }},
      {"supersampling", "sampling", "K", "quadrature: aperture samples per view step (default: about |slope|)", false,
       LFCAM_FIELD(whole("supersampling", text), supersampling)},
      {"upsample", "sampling", "K",
       "render on a grid K times finer (1: off); a flat focus through the whole lens places each view's samples "
       "where they land: detail finer than the microlenses away from their plane",
       false, LFCAM_FIELD(whole("upsample", text), upsample)},
  }};
  return fields;
}

#undef LFCAM_FIELD

const PhotoField* findPhotoField(const std::string& name) {
  std::string dashed = name;
  std::replace(dashed.begin(), dashed.end(), '_', '-');
  if (dashed == "aperture-center") dashed = "aperture-centre";  // the spelling of earlier versions
  for (const PhotoField& field : photoFields())
    if (dashed == field.name) return &field;
  return nullptr;
}

Status setPhotoField(PhotoRequest& request, const std::string& name, const std::string& text) {
  const PhotoField* field = findPhotoField(name);
  if (!field) return usage("unknown photograph setting " + quoted(name));
  return field->parse(request, text);
}

Status checkPhotoRequest(const PhotoRequest& r) {
  const int focusModels = int(r.slope.has_value()) + int(r.alpha.has_value()) + int(r.focusAt.has_value()) +
                          int(r.focusPlane.has_value()) + int(r.focusRange.has_value());
  if (focusModels != 1)
    return usage(std::string(focusModels ? "give one focus only" : "give the focus") +
                 ": slope, alpha, focus-at, focus-plane or focus-range");
  if (r.tilt && !(r.slope || r.alpha || r.focusAt))
    return usage("tilt tilts the focus of slope, alpha or focus-at (focus-plane and focus-range set their own)");
  if (r.tiltDirection && !r.tilt) return usage("tilt-direction goes with tilt");
  if (r.depth && !r.focusRange) return usage("depth goes with focus-range");
  if (r.alpha && !(*r.alpha > 0)) return usage("alpha: must be positive");
  if (const auto& range = r.focusRange) {
    if (!range->millimetres && range->nearEnd < range->farEnd) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "focus-range: the near end (slope %g) lies behind the far end (slope %g); slopes grow towards "
                    "the camera",
                    range->nearEnd, range->farEnd);
      return usage(text);
    }
    if (range->millimetres && (!(range->nearEnd > 0) || range->nearEnd > range->farEnd))
      return usage("focus-range: the near distance must be positive and no farther than the far one");
  }
  if (r.aperture && !(*r.aperture >= 0)) return usage("aperture: the radius must be 0 or more");
  if (r.fNumber && !(*r.fNumber >= 1))
    return usage("f-number: must be 1 (the whole lens) or more; the lens admits no wider aperture");
  if (r.aperture && r.fNumber) return usage("aperture and f-number set the same radius: give one");
  if (r.apertureMask && (r.aperture || r.fNumber || r.apertureShape))
    return usage("aperture-mask is the aperture's shape and size: no aperture, f-number or aperture-shape with it");
  if (r.apertureMask && r.apertureMask->empty()) return usage("aperture-mask: the image is empty");
  if (r.apertureShape && !(r.aperture || r.fNumber)) return usage("aperture-shape needs aperture or f-number");
  if (r.apertureCentre && !(r.aperture || r.fNumber || r.apertureMask))
    return usage("aperture-centre moves an aperture: give aperture, f-number or aperture-mask");
  if (r.beta && !(*r.beta > 0)) return usage("beta: must be positive");
  if (r.supersampling < 0 || r.supersampling > 32) return usage("supersampling: expected 1 to 32");
  if (r.supersampling && r.method != PhotoMethod::Quadrature) return usage("supersampling goes with method quadrature");
  if (r.upsample < 1 || r.upsample > kMaxUpsampleFactor)
    return usage("upsample: expected 1 to " + std::to_string(kMaxUpsampleFactor) + ", got " +
                 std::to_string(r.upsample));
  if (r.method == PhotoMethod::Fourier && (r.tilt || r.focusPlane || r.focusRange || r.aperture || r.fNumber ||
                                           r.apertureMask || r.clamp || (r.beta && *r.beta != 1) || r.upsample != 1))
    return usage(
        "method fourier renders a flat focus through the whole lens only (no tilt, focus-plane, "
        "focus-range, aperture, beta, clamp or upsample): use fast or quadrature");
  return {};
}

namespace {

std::string named(const ResolveOptions& options) {
  return options.inputName.empty() ? "light field" : options.inputName;
}

Result<double> parallaxOf(const LightField& lightField, const ResolveOptions& options, const char* what) {
  const auto& optics = lightField.metadata.optics;
  if (!optics || !(optics->spatialStepMm > 0) || !(optics->lensStepMm > 0))
    return usage(named(options) + ": no optics metadata, so " + what);
  return optics->lensStepMm / optics->spatialStepMm;
}

}  // namespace

Status checkImagePoint(const LightField& lightField, const char* name, const ImagePoint& point) {
  if (point[0] >= 0 && point[0] < lightField.ns() && point[1] >= 0 && point[1] < lightField.nt()) return {};
  char text[160];
  std::snprintf(text, sizeof text, "%s: point %g,%g lies outside the %dx%d image", name, point[0], point[1],
                lightField.ns(), lightField.nt());
  return usage(text);
}

namespace {

Result<ResolvedFilm> resolveFilm(const PhotoRequest& r, const LightField& lightField, const ResolveOptions& options) {
  ResolvedFilm film;
  film.plane.centreX = 0.5 * lightField.ns();
  film.plane.centreY = 0.5 * lightField.nt();
  if (r.focusPlane) {
    auto plane = focusPlaneThroughPoints(lightField, *r.focusPlane, options.search);
    if (!plane) return usage("focus-plane: " + plane.error().message);
    film.plane = *plane;
    return film;
  }
  if (r.focusRange) {
    double nearSlope = r.focusRange->nearEnd, farSlope = r.focusRange->farEnd;
    if (r.focusRange->millimetres) {
      const auto& optics = lightField.metadata.optics;
      if (!optics)
        return usage(named(options) +
                     ": focus-range in mm needs the optics (focal length), which this light field does not record; "
                     "give the range in slopes");
      const auto nearFound = disparityFromDistance(*optics, nearSlope);
      const auto farFound = disparityFromDistance(*optics, farSlope);
      if (!nearFound || !farFound)
        return usage(named(options) + ": focus-range in mm needs a focal length, and distances beyond it");
      nearSlope = *nearFound, farSlope = *farFound;
    }
    film.range = std::array<double, 2>{farSlope, nearSlope};
    if (r.depth) {
      if (Status checked = checkFocusSpread(lightField, *r.depth, farSlope, nearSlope); !checked)
        return usage("depth: " + checked.error().message);
      film.depth = r.depth;
    } else {
      auto estimated = estimateDepth(lightField);
      if (!estimated) return makeError(estimated.error().code, named(options) + ": " + estimated.error().message);
      film.depth = std::make_shared<const Image>(std::move(estimated->disparity));
    }
    return film;
  }
  double slope = r.slope.value_or(0.0);
  if (r.alpha) {
    LFCAM_ASSIGN_OR_RETURN(slope, slopeFromAlpha(lightField, *r.alpha, named(options)));
  }
  if (r.focusAt) {
    LFCAM_TRY(checkImagePoint(lightField, "focus-at", *r.focusAt));
    auto found = slopeAtPixel(lightField, (*r.focusAt)[0], (*r.focusAt)[1], options.search);
    if (!found) return makeError(found.error().code, "focus-at: " + found.error().message);
    slope = *found;
  }
  if (r.tilt) return ResolvedFilm{focusPlaneFromTilt(lightField, slope, *r.tilt, r.tiltDirection.value_or(0)), {}, {}};
  film.plane.slope = slope;
  return film;
}

// A circle or square that can fall between the views (narrower than half a view diagonal, or a
// square of half side under half a view) lets no view through where it sits between them: with
// the fast method, such an aperture is a pinhole at its centre, one ray per pixel interpolated
// between the views (Equation 7's observer).
bool narrowerThanAView(const Aperture& aperture) {
  return (aperture.shape == Aperture::Shape::Circle && aperture.radius < std::sqrt(0.5)) ||
         (aperture.shape == Aperture::Shape::Square && aperture.radius < 0.5);
}

Result<Aperture> resolveAperture(const PhotoRequest& r, const LightField& lightField) {
  const auto [u, v] = r.apertureCentre.value_or(std::array<double, 2>{0, 0});
  if (r.apertureMask) {
    // Laid over the whole lens, a mask of other proportions than the lens would stretch its shape.
    const Image& mask = *r.apertureMask;
    const double stretch = double(mask.width()) * lightField.nv() / (double(mask.height()) * lightField.nu());
    if (std::abs(std::log(stretch)) > std::log(1 + 1.0 / std::min(mask.width(), mask.height())) + 1e-9)
      return usage("aperture-mask: the mask is " + std::to_string(mask.width()) + "x" + std::to_string(mask.height()) +
                   " pixels, the lens " + std::to_string(lightField.nu()) + "x" + std::to_string(lightField.nv()) +
                   " views: it must have the lens's proportions");
    return Aperture{Aperture::Shape::Mask, 0, u, v, r.apertureMask};
  }
  if (!r.aperture && !r.fNumber) return Aperture::full();
  const double lensRadius = 0.5 * std::max(lightField.nu(), lightField.nv());
  const double radius = r.aperture ? *r.aperture : lensRadius / *r.fNumber;
  return r.apertureShape.value_or("circle") == "square" ? Aperture::square(radius, u, v)
                                                        : Aperture::circle(radius, u, v);
}

}  // namespace

Result<ResolvedPhoto> resolvePhoto(const PhotoRequest& request, const LightField& lightField,
                                   const ResolveOptions& options) {
  LFCAM_TRY(checkPhotoRequest(request));
  if (lightField.empty()) return usage(named(options) + ": the light field is empty");
  ResolvedPhoto photo;
  LFCAM_ASSIGN_OR_RETURN(photo.aperture, resolveAperture(request, lightField));
  photo.pinhole = request.method == PhotoMethod::Fast && narrowerThanAView(photo.aperture);
  photo.clamp = request.clamp;
  // On the real lens plane a pinhole's one ray needs a view within a step of it.
  const Aperture& a = photo.aperture;
  if (photo.pinhole && !photo.clamp && !(request.beta && *request.beta != 1) &&
      !(std::abs(a.centreU) < 0.5 * (lightField.nu() + 1) && std::abs(a.centreV) < 0.5 * (lightField.nv() + 1))) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "aperture-centre: a pinhole at %g,%g lies off the lens (%dx%d views, %g,%g the outermost); clamp "
                  "keeps it on",
                  a.centreU, a.centreV, lightField.nu(), lightField.nv(), 0.5 * (lightField.nu() - 1),
                  0.5 * (lightField.nv() - 1));
    return usage(text);
  }
  if (request.beta && *request.beta != 1) {
    photo.beta = *request.beta;
    LFCAM_ASSIGN_OR_RETURN(photo.parallax,
                           parallaxOf(lightField, options, "the lens plane cannot be moved (beta); leave beta at 1"));
  }
  photo.method = request.method;
  photo.supersampling = request.supersampling;
  photo.upsample = request.upsample;
  if (request.focusPlane)
    for (const ImagePoint& point : *request.focusPlane) LFCAM_TRY(checkImagePoint(lightField, "focus-plane", point));
  LFCAM_ASSIGN_OR_RETURN(photo.film, resolveFilm(request, lightField, options));
  // A flat film with the lens plane moved: a film at infinity or on the lens plane is an error
  // rather than a black photograph.
  if (!photo.film.depth && photo.film.plane.gradientX == 0 && photo.film.plane.gradientY == 0)
    LFCAM_TRY(rayMap(photo.film.plane.slope, photo.beta, photo.parallax));
  return photo;
}

Result<double> slopeFromAlpha(const LightField& lightField, double alpha, const std::string& inputName) {
  if (!(alpha > 0)) return usage("alpha must be positive, got " + std::to_string(alpha));
  const auto& optics = lightField.metadata.optics;
  if (!optics)
    return usage(inputName +
                 ": no optics metadata, so alpha cannot be converted to a slope; give the slope (pixels per view "
                 "step)");
  return optics->slopeFromAlpha(alpha);
}

}  // namespace lfcam
