// The interactive viewer behind `lfcam view`: a light field held in memory and the photographs a
// page asks for (click to focus, focus, aperture, observer position, a tilted plane of focus
// through three clicked points, a focus range, a finer grid, all-in-focus and depth layers),
// answered as JPEG bytes. Requests are plain values (ViewerRequest, ViewerAnswer) routed
// by answerRequest, independent of the HTTP library, so that routing, parsing and limits are
// unit-tested without a socket; viewer_server.hpp puts them on the network.
//
// Bounds, so that a page left open (or a hostile client) cannot grow the process: answers are
// cached up to `cacheBytes`, at most `concurrentRenders` photographs are rendered at once (a
// request that waits longer than `renderWaitSeconds` for its turn gets 503), every number is
// checked against a range, and nothing but the embedded page and the answers computed from the
// one light field can be read: no path of a request ever reaches the file system.
//
// The all-in-focus photograph and the depth map are slow (about 60-130 refocus times, depth.hpp,
// all_in_focus.hpp): the first request for one computes it in its own (server) thread, and
// while it runs every other request for it answers 202 with the estimated progress, so the page
// can poll /api/status and stay responsive. A focus range (focus_spread.hpp) needs the depth map:
// it answers 202 in the same way until the depth layer is ready, then renders on its disparity.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/photo/photo_request.hpp"
#include "lfcam/render/tilted_focus.hpp"

namespace lfcam {

enum class ViewerLayer { Photo, AllInFocus, Depth };

// One photograph as the page describes it: the photo layer's fields of the photograph request
// (photo_request.hpp) by name, as the query gave them (no focus: slope 0), or another layer.
struct ViewerView {
  ViewerLayer layer = ViewerLayer::Photo;
  std::map<std::string, std::string> photo;  // "slope" -> "0.5", "f-number" -> "2", ...
  int quality = 80;                          // JPEG quality
};

struct ViewerLimits {
  std::size_t cacheBytes = std::size_t(64) << 20;
  int concurrentRenders = 2;
  double renderWaitSeconds = 10;
};

class ViewerSession {
 public:
  explicit ViewerSession(LightField lightField, ViewerLimits limits = {});
  ~ViewerSession();
  ViewerSession(const ViewerSession&) = delete;
  ViewerSession& operator=(const ViewerSession&) = delete;

  const LightField& lightField() const;
  // The slope range the page's focus slider spans (metadata, else [-4, 4]) and the lens radius
  // (view steps) that fNumber 1 opens.
  double slopeMin() const;
  double slopeMax() const;
  double lensRadius() const;

  // JSON: size, views, slope range, lens radius, the f-number of the whole lens when the optics
  // say it, and the source.
  std::string infoJson() const;
  // JSON: the state of the slow layers: {"allInFocus": {"state": "idle|running|ready|failed",
  // "progress": 0..1, "error": ...}, "depth": {...}}. Progress while running is estimated from
  // the time one refocus takes.
  std::string statusJson() const;

  // The focus search of a click and of each point of a tilted plane: the slider's range.
  FocusSearch focusSearch() const;
  // The slope that makes pixel (x, y) sharpest (slopeAtPixel over the slider's range).
  Result<double> focusAt(double x, double y) const;

  struct Photo {
    std::string jpeg;
    double slope = 0;                 // the slope rendered (the one chosen, for a click)
    std::optional<FocusPlane> plane;  // the tilted plane rendered, for focusPlane
    bool cached = false;
  };
  // The photograph `view` describes. Errors: Usage for a view the light field refuses (the request's
  // own one-line message);
  // Resource when the render queue is full (503) or when the layer is being computed by another
  // request (202: poll statusJson).
  Result<Photo> render(const ViewerView& view);

  // Bytes held by the answer cache (never more than ViewerLimits::cacheBytes).
  std::size_t cacheBytes() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// A request as the HTTP layer hands it over: method, path (no query), and query parameters.
struct ViewerRequest {
  std::string method = "GET";
  std::string path;
  std::multimap<std::string, std::string> params;
};

struct ViewerAnswer {
  int status = 200;
  std::string contentType = "text/plain; charset=utf-8";
  std::string body;
  std::map<std::string, std::string> headers;
};

// Routes:
//   GET /, /index.html, /viewer.js, /viewer.css   the embedded page
//   GET /api/info, /api/status                    JSON (above)
//   GET /api/focus?x=X&y=Y                         {"slope": D}
//   GET /api/image?layer=photo|allinfocus|depth&q=Q&NAME=TEXT...
//       every field of the photograph request that is not a file, by its name (photoFields():
//       slope, focus-at, f-number, aperture-centre, focus-plane, focus-range, upsample, ...);
//       image/jpeg, the slope rendered in header X-Lfcam-Slope (for a tilted plane, at the image
//       centre, and the plane in X-Lfcam-Plane: "slope,gradientX,gradientY"); every parameter optional
// Anything else: 404 (unknown path), 405 (not GET/HEAD), 400 (a bad, unknown or repeated
// parameter, or a request the photograph request refuses: its one line), 202 (layer being
// computed, or the depth map a range needs), 503 (render queue full).
ViewerAnswer answerRequest(ViewerSession& session, const ViewerRequest& request);

// The parameters of /api/image, checked (400 material on error) against the light field.
Result<ViewerView> parseViewerView(const std::multimap<std::string, std::string>& params, const ViewerSession& session);

}  // namespace lfcam
