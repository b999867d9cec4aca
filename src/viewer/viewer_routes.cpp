// answerRequest: the viewer's routes and the checking of their parameters, without sockets.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <set>

#include <nlohmann/json.hpp>

#include "lfcam/photo/photo_request.hpp"
#include "lfcam/viewer/viewer.hpp"
#include "viewer/viewer_assets.hpp"

namespace lfcam {

namespace {

ViewerAnswer text(int status, std::string message) {
  return {status, "text/plain; charset=utf-8", std::move(message) + "\n", {}};
}

ViewerAnswer json(int status, std::string body) { return {status, "application/json", std::move(body), {}}; }

// A whole finite number, nothing else ("1e3" yes, "1x", "", "nan" no).
std::optional<double> parseNumber(const std::string& text) {
  double value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

Result<double> numberIn(const std::string& name, const std::string& text, double low, double high) {
  auto value = parseNumber(text);
  if (!value || *value < low || *value > high) {
    char range[96];
    std::snprintf(range, sizeof range, "a number in [%g, %g]", low, high);
    return makeError(ErrorCode::Usage, "parameter " + name + ": expected " + range);
  }
  return *value;
}

// Each name at most once, and only the names a route knows.
Status checkNames(const std::multimap<std::string, std::string>& params, const std::set<std::string>& known) {
  for (auto it = params.begin(); it != params.end(); it = params.upper_bound(it->first)) {
    if (!known.count(it->first))
      return makeError(ErrorCode::Usage, "unknown parameter '" + it->first.substr(0, 40) + "'");
    if (params.count(it->first) > 1) return makeError(ErrorCode::Usage, "parameter " + it->first + " given twice");
  }
  return {};
}

const std::string* param(const std::multimap<std::string, std::string>& params, const std::string& name) {
  auto it = params.find(name);
  return it == params.end() ? nullptr : &it->second;
}

}  // namespace

Result<ViewerView> parseViewerView(const std::multimap<std::string, std::string>& params,
                                   const ViewerSession& session) {
  std::set<std::string> known{"layer", "q"};
  for (const PhotoField& field : photoFields())
    if (!field.fromFile) known.insert(field.name);
  LFCAM_TRY(checkNames(params, known));
  const LightField& lf = session.lightField();
  ViewerView view;
  if (auto* layer = param(params, "layer")) {
    if (*layer == "photo")
      view.layer = ViewerLayer::Photo;
    else if (*layer == "allinfocus")
      view.layer = ViewerLayer::AllInFocus;
    else if (*layer == "depth")
      view.layer = ViewerLayer::Depth;
    else
      return makeError(ErrorCode::Usage, "parameter layer: expected photo, allinfocus or depth");
  }
  if (auto* q = param(params, "q")) {
    LFCAM_ASSIGN_OR_RETURN(auto value, numberIn("q", *q, 10, 100));
    view.quality = int(std::lround(value));
  }
  PhotoRequest request;
  for (const auto& [name, text] : params)
    if (name != "layer" && name != "q") {
      LFCAM_TRY(setPhotoField(request, name, text));
      view.photo[name] = text;
    }
  if (view.layer != ViewerLayer::Photo) {
    if (!view.photo.empty())
      return makeError(ErrorCode::Usage, "the layers allinfocus and depth take no photo setting");
    return view;
  }
  // No focus setting at all: the focus of the lens as it was (slope 0).
  if (!request.slope && !request.alpha && !request.focusAt && !request.focusPlane && !request.focusRange &&
      !request.tilt && !request.tiltDirection)
    request.slope = 0.0, view.photo["slope"] = "0";
  LFCAM_TRY(checkPhotoRequest(request));
  // Slopes beyond the image's width shift every view out of the picture: nothing to see there.
  const double slopeLimit = std::max(8.0, double(std::max(lf.ns(), lf.nt())));
  if (request.slope && std::abs(*request.slope) > slopeLimit)
    return makeError(ErrorCode::Usage, "slope: expected a number in [" + std::to_string(-slopeLimit) + ", " +
                                           std::to_string(slopeLimit) + "]");
  // The observer stays on the lens: clamped to its views rather than refused, as a drag overshoots.
  if (request.apertureCentre) {
    const double halfU = 0.5 * (lf.nu() - 1), halfV = 0.5 * (lf.nv() - 1);
    char centre[64];
    std::snprintf(centre, sizeof centre, "%.6g,%.6g", std::clamp((*request.apertureCentre)[0], -halfU, halfU),
                  std::clamp((*request.apertureCentre)[1], -halfV, halfV));
    view.photo["aperture-centre"] = centre;
  }
  return view;
}

ViewerAnswer answerRequest(ViewerSession& session, const ViewerRequest& request) {
  if (request.method != "GET" && request.method != "HEAD") {
    ViewerAnswer answer = text(405, "only GET");
    answer.headers["Allow"] = "GET, HEAD";
    return answer;
  }
  const std::string& path = request.path;
  std::string assetName = path == "/" || path == "/index.html" ? "viewer.html" : path.substr(path.empty() ? 0 : 1);
  // Only the viewer's own files; the export's template is not a page of the server.
  if (assetName.rfind("viewer.", 0) == 0) {
    if (const viewer::Asset* asset = viewer::findAsset(assetName)) {
      if (!request.params.empty()) return text(400, "the page takes no parameters");
      ViewerAnswer answer{200, std::string(asset->contentType), std::string(asset->bytes), {}};
      answer.headers["Cache-Control"] = "no-cache";
      return answer;
    }
  }
  if (path == "/api/info" || path == "/api/status") {
    if (!request.params.empty()) return text(400, path + " takes no parameters");
    return json(200, path == "/api/info" ? session.infoJson() : session.statusJson());
  }
  if (path == "/api/focus") {
    if (Status names = checkNames(request.params, {"x", "y"}); !names) return text(400, names.error().message);
    const std::string *x = param(request.params, "x"), *y = param(request.params, "y");
    if (!x || !y) return text(400, "parameters x and y are required");
    auto px = parseNumber(*x), py = parseNumber(*y);
    if (!px || !py) return text(400, "parameters x and y must be numbers");
    auto slope = session.focusAt(*px, *py);
    if (!slope) return text(slope.error().code == ErrorCode::Usage ? 400 : 500, slope.error().message);
    return json(200, nlohmann::json{{"slope", *slope}}.dump());
  }
  if (path == "/api/image") {
    auto view = parseViewerView(request.params, session);
    if (!view) return text(400, view.error().message);
    auto photo = session.render(*view);
    if (!photo) {
      const Error& error = photo.error();
      if (error.code == ErrorCode::Usage) return text(400, error.message);
      if (error.code == ErrorCode::Resource && error.message == "running") return json(202, session.statusJson());
      if (error.code == ErrorCode::Resource) {
        ViewerAnswer answer = text(503, error.message);
        answer.headers["Retry-After"] = "1";
        return answer;
      }
      return text(500, error.message);
    }
    ViewerAnswer answer{200, "image/jpeg", std::move(photo->jpeg), {}};
    char slope[32];
    std::snprintf(slope, sizeof slope, "%.6f", photo->slope);
    answer.headers["X-Lfcam-Slope"] = slope;
    if (const auto& plane = photo->plane) {
      char text[96];
      std::snprintf(text, sizeof text, "%.6f,%.8f,%.8f", plane->slope, plane->gradientX, plane->gradientY);
      answer.headers["X-Lfcam-Plane"] = text;
    }
    answer.headers["X-Lfcam-Cached"] = photo->cached ? "1" : "0";
    answer.headers["Cache-Control"] = "no-store";
    return answer;
  }
  return text(404, "not found");
}

}  // namespace lfcam
