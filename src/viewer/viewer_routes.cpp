// answerRequest: the viewer's routes and the checking of their parameters, without sockets.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <set>

#include <nlohmann/json.hpp>

#include "lfcam/upsampled_refocus.hpp"
#include "lfcam/viewer.hpp"
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

// "NEAR:FAR" in slopes within the session's range, near the larger -> {far, near}; the command
// line's --focus-range wording.
Result<std::pair<double, double>> parseFocusRange(const std::string& text, const ViewerSession& session) {
  const auto colon = text.find(':');
  const auto nearEnd = parseNumber(text.substr(0, colon)),
             farEnd = colon == std::string::npos ? std::nullopt : parseNumber(text.substr(colon + 1));
  char expected[128];
  std::snprintf(expected, sizeof expected, "parameter range: expected NEAR:FAR as slopes in [%g, %g]",
                session.slopeMin(), session.slopeMax());
  if (!nearEnd || !farEnd) return makeError(ErrorCode::Usage, expected);
  if (*nearEnd < *farEnd)
    return makeError(ErrorCode::Usage, "parameter range: the near end (slope " + text.substr(0, colon) +
                                           ") lies behind the far end (slope " + text.substr(colon + 1) +
                                           "); slopes grow towards the camera");
  if (*farEnd < session.slopeMin() || *nearEnd > session.slopeMax()) return makeError(ErrorCode::Usage, expected);
  return std::pair{*farEnd, *nearEnd};
}

// The tilted plane, the focus range and the finer grid: each value checked, at most one of them,
// and each with the whole lens from its centre (as the command line's refocus accepts them).
Status parseFocusShape(const std::multimap<std::string, std::string>& params, const ViewerSession& session,
                       ViewerView& view) {
  if (auto* plane = param(params, "plane")) {
    auto points = parseFocusPlanePoints(*plane);
    Status valid = points ? checkFocusPlanePoints(session.lightField(), *points) : Status(points.error());
    if (!valid) return makeError(ErrorCode::Usage, "parameter plane: " + valid.error().message);
    view.focusPlane = *points;
  }
  if (auto* range = param(params, "range")) {
    LFCAM_ASSIGN_OR_RETURN(auto value, parseFocusRange(*range, session));
    view.focusRange = value;
  }
  if (auto* upsample = param(params, "upsample")) {
    const auto value = parseNumber(*upsample);
    if (!value || *value != std::floor(*value) || *value < 1 || *value > kMaxUpsampleFactor)
      return makeError(ErrorCode::Usage, "parameter upsample: expected 1 to " + std::to_string(kMaxUpsampleFactor) +
                                             ", got '" + upsample->substr(0, 20) + "'");
    view.upsample = int(*value);
  }
  const int shapes = int(view.focusPlane.has_value()) + int(view.focusRange.has_value()) + int(view.upsample > 1);
  if (shapes == 0) return {};
  if (shapes > 1) return makeError(ErrorCode::Usage, "parameters plane, range and upsample: at most one at a time");
  if (view.layer != ViewerLayer::Photo || view.fNumber != 1 || view.u != 0 || view.v != 0)
    return makeError(ErrorCode::Usage,
                     "parameters plane, range and upsample render the photo layer with the whole lens from its "
                     "centre only (no f, u or v)");
  if ((view.focusPlane || view.focusRange) && (param(params, "slope") || view.focusAt))
    return makeError(ErrorCode::Usage, "parameters plane and range set the focus themselves (no slope or focus)");
  return {};
}

}  // namespace

Result<ViewerView> parseViewerView(const std::multimap<std::string, std::string>& params,
                                   const ViewerSession& session) {
  LFCAM_TRY(checkNames(params, {"layer", "slope", "focus", "f", "u", "v", "q", "plane", "range", "upsample"}));
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
  // Slopes beyond the image's width shift every view out of the picture: nothing to see there.
  const double slopeLimit = std::max(8.0, double(std::max(lf.ns(), lf.nt())));
  if (auto* slope = param(params, "slope")) {
    LFCAM_ASSIGN_OR_RETURN(auto value, numberIn("slope", *slope, -slopeLimit, slopeLimit));
    view.slope = value;
  }
  if (auto* focus = param(params, "focus")) {
    const auto comma = focus->find(',');
    if (comma == std::string::npos) return makeError(ErrorCode::Usage, "parameter focus: expected X,Y");
    LFCAM_ASSIGN_OR_RETURN(const double x,
                           numberIn("focus", focus->substr(0, comma), 0, std::nextafter(double(lf.ns()), 0.0)));
    LFCAM_ASSIGN_OR_RETURN(const double y,
                           numberIn("focus", focus->substr(comma + 1), 0, std::nextafter(double(lf.nt()), 0.0)));
    view.focusAt = std::pair{x, y};
  }
  if (auto* f = param(params, "f")) {
    LFCAM_ASSIGN_OR_RETURN(auto value, numberIn("f", *f, 1, 1000));
    view.fNumber = value;
  }
  // The observer stays on the lens: clamped to its views rather than refused, as a drag overshoots.
  for (const char* axis : {"u", "v"}) {
    if (auto* text = param(params, axis)) {
      LFCAM_ASSIGN_OR_RETURN(auto value, numberIn(axis, *text, -1000, 1000));
      const double half = 0.5 * ((axis[0] == 'u' ? lf.nu() : lf.nv()) - 1);
      (axis[0] == 'u' ? view.u : view.v) = std::clamp(value, -half, half);
    }
  }
  if (auto* q = param(params, "q")) {
    LFCAM_ASSIGN_OR_RETURN(auto value, numberIn("q", *q, 10, 100));
    view.quality = int(std::lround(value));
  }
  LFCAM_TRY(parseFocusShape(params, session, view));
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
