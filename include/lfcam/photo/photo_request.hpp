// PhotoRequest: one synthetic photograph as Equation 5 (with Equation 7 for the observer) describes
// it, whole: a film plane (flat at a depth, tilted, or bent over a range of depths by a depth map),
// a lens aperture (size, shape or mask, centre), the lens plane (beta), a sampling (method and
// grid). Every combination of them renders: renderPhoto picks the fast kernel where one exists and
// the general per-pixel path (every ray interpolated quadrilinearly, float32) elsewhere.
//
// The fields are described once, by photoFields(): name, group, syntax, help and the parser of
// their text. The command line's flags (--NAME), Python's keywords (NAME with '_' for '-'), the
// viewer's query parameters and batch specs all come from that table, so that they accept and
// refuse the same requests with the same one-line messages (checkPhotoRequest for what needs no
// light field, resolvePhoto for the rest).
//
// Units as in light_field.hpp: slopes in pixels per view step (the HCI convention's disparity),
// aperture radius and centre in view steps from the lens centre, image points in pixels.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/render/focal_stack.hpp"
#include "lfcam/render/synthetic_camera.hpp"
#include "lfcam/render/tilted_focus.hpp"

namespace lfcam {

enum class PhotoMethod {
  Fast,        // the aperture sampled at the views (shift-and-add where the film is flat, beta 1)
  Quadrature,  // the aperture supersampled between the views (section 5.2): no ghosts far from focus
  Fourier,     // Fourier slice refocusing: one 4D FFT, then each flat full-aperture photo from a 2D slice
};

// Everything between two depths in focus (focus_spread.hpp); slopes, or millimetres from the main
// lens (needs the optics), the near end the larger slope / the smaller distance.
struct FocusRange {
  double nearEnd = 0, farEnd = 0;
  bool millimetres = false;
};

struct PhotoRequest {
  // The film: exactly one of slope, alpha, focusAt, focusPlane and focusRange.
  std::optional<double> slope;
  std::optional<double> alpha;                          // relative film depth (needs optics)
  std::optional<ImagePoint> focusAt;                    // the depth that makes this pixel sharpest
  std::optional<std::array<ImagePoint, 3>> focusPlane;  // the plane through three points, each at its sharpest
  std::optional<double> tilt;           // with slope, alpha or focusAt: slope change over one image width
  std::optional<double> tiltDirection;  // degrees the slope grows towards (0: right)
  std::optional<FocusRange> focusRange;
  std::shared_ptr<const Image> depth;  // with focusRange: disparity of the centre view (default: estimated)

  // The aperture: the whole lens, or a radius (or an f-number), a shape or a mask, and a centre.
  std::optional<double> aperture;                       // radius, view steps; 0: a pinhole
  std::optional<double> fNumber;                        // relative to the whole lens (1): radius = lens radius / f
  std::optional<std::string> apertureShape;             // "circle" (default) or "square"
  std::optional<std::array<double, 2>> apertureCentre;  // (u, v): also where the observer stands
  std::shared_ptr<const Image> apertureMask;
  bool clamp = false;  // a ray that leaves the lens takes the outermost view's (Figure 7)

  std::optional<double> beta;  // synthetic lens plane (needs optics)

  PhotoMethod method = PhotoMethod::Fast;
  int supersampling = 0;  // Quadrature: aperture samples per view step (0: about |slope|)
  int upsample = 1;       // the photograph on a grid this many times finer (upsampled_refocus.hpp)
};

// One field of PhotoRequest as every front end names it.
struct PhotoField {
  const char* name;    // "focus-plane": --focus-plane, focus_plane=, ?focus-plane=
  const char* group;   // focus, aperture, lens, sampling
  const char* syntax;  // "X1,Y1:X2,Y2:X3,Y3"
  const char* help;
  bool fromFile;  // its text names an image file (Python: an array); not a viewer parameter
  // Sets the field from its text. Usage error, naming the field, for text it cannot be.
  Status (*parse)(PhotoRequest& request, const std::string& text);
};
std::span<const PhotoField> photoFields();
const PhotoField* findPhotoField(const std::string& name);  // by name, '_' read as '-'

// Sets fields from name=text pairs (a viewer query, a batch spec); an unknown name is a usage error.
// Fields read from files (fromFile) are read here too.
Status setPhotoField(PhotoRequest& request, const std::string& name, const std::string& text);

// What can be checked without the light field: one focus model, the fields that need another, the
// ranges. Usage errors, one line each.
Status checkPhotoRequest(const PhotoRequest& request);

// Usage error "NAME: point X,Y lies outside the WxH image" unless the point lies in the views.
Status checkImagePoint(const LightField& lightField, const char* name, const ImagePoint& point);

// The film a request resolves to on one light field: a plane in (x, y, slope) (gradient 0 when
// flat), or a range over a disparity map.
struct ResolvedFilm {
  FocusPlane plane;
  std::optional<std::array<double, 2>> range;  // {far, near} slopes, on `depth`
  std::shared_ptr<const Image> depth;
};

// A request resolved against one light field: the searches done (focusAt, focusPlane), the depth
// map estimated when a range needs one, the aperture and lens plane in the light field's units.
struct ResolvedPhoto {
  ResolvedFilm film;
  Aperture aperture;
  bool pinhole = false;  // one ray per pixel through the aperture's centre, interpolated between views
  bool clamp = false;
  double beta = 1, parallax = 0;
  PhotoMethod method = PhotoMethod::Fast;
  int supersampling = 0;
  int upsample = 1;
};

struct ResolveOptions {
  FocusSearch search;     // of focusAt and focusPlane's points
  std::string inputName;  // starts messages about the light field's metadata
};

// Usage errors: those of checkPhotoRequest, and what the light field refuses (alpha, beta or a
// range in mm without optics, points outside the image, a depth map or mask of the wrong size).
Result<ResolvedPhoto> resolvePhoto(const PhotoRequest& request, const LightField& lightField,
                                   const ResolveOptions& options = {});

// The photograph: (upsample ns) x (upsample nt) pixels, the light field's channels, normalised by
// the weight of the rays that arrived (section 5.2).
Result<Image> renderPhoto(const LightField& lightField, const ResolvedPhoto& photo);
Result<Image> renderPhoto(const LightField& lightField, const PhotoRequest& request,
                          const ResolveOptions& options = {});

// The float64 per-pixel evaluation of the same photograph, single-threaded: the oracle every
// kernel renderPhoto picks is tested against.
Result<Image> renderPhotoReference(const LightField& lightField, const ResolvedPhoto& photo);

// One photograph per slope of a flat film, the rest of `photo` as resolved (a focal stack), handed
// to `sink` in order; the Fourier method computes its spectrum once. Stops at the first error.
Status renderPhotos(const LightField& lightField, const ResolvedPhoto& photo, const std::vector<double>& slopes,
                    const std::function<Status(int index, double slope, Image&& photo)>& sink);

// The slope of the relative film depth alpha (Equation 6) for this light field's optics.
Result<double> slopeFromAlpha(const LightField& lightField, double alpha, const std::string& inputName);

}  // namespace lfcam
