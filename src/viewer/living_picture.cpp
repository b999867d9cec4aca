// makeLivingPicture: focal stack, per-pixel sharpest slice and viewpoint sweep in one HTML page;
// makeLytroLivingPicture: the same page over a Lytro container's own stored slices and depth map.
#include "lfcam/viewer/living_picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/photo/photo_request.hpp"
#include "viewer/image_encode.hpp"
#include "viewer/living_page.hpp"

namespace lfcam {

namespace {

// A number as text that reads back to the same double.
std::string exact(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// One photograph of the page rendered from its photograph request (photo_request.hpp), given as
// the fields' name=text pairs; the request's text is kept beside the image (as the viewer's query:
// lfcam view answers /api/image?TEXT with the same photograph), so that every control of the page
// shows a request of the one table. `depth`: a focus range's map.
Result<nlohmann::json> requestedPhoto(const LightField& lightField,
                                      const std::vector<std::pair<std::string, std::string>>& fields,
                                      const std::shared_ptr<const Image>& depth, int quality) {
  PhotoRequest request;
  std::string text;
  for (const auto& [name, value] : fields) {
    LFCAM_TRY(setPhotoField(request, name, value));
    text += (text.empty() ? "" : "&") + name + "=" + value;
  }
  request.depth = depth;
  LFCAM_ASSIGN_OR_RETURN(auto photo, renderPhoto(lightField, request));
  LFCAM_ASSIGN_OR_RETURN(auto url, dataUrl(photo, quality));
  return nlohmann::json{{"request", text}, {"image", url}};
}

// The small aperture: a third of the lens's radius in views, at least one view step.
double smallApertureRadius(const LightField& lightField) {
  return std::max(1.0, (std::min(lightField.nu(), lightField.nv()) - 1) / 6.0);
}

// The focus range slider's stops (slice indices, ascending) and, for every pair of distinct stops,
// the photograph with everything between them in focus: refocusSpread on the depth map estimated
// over the stack's slopes. Precomputed rather than picked per pixel from the slices in the page: a
// slice focused beside a nearer surface carries that surface's blur over the pixels around it, a
// ring that refocusSpread leaves out by dropping the rays the nearer surface hides. The depth map,
// not the all-in-focus labels: a label one slice off its neighbours (noise on a flat wall) makes
// them hide all of its rays, a black dot.
Status addFocusRanges(const LightField& lightField, const std::vector<double>& slopes,
                      const LivingPictureOptions& options, const std::function<void(double)>& report,
                      nlohmann::json& data) {
  const int slices = int(slopes.size()), ends = std::min(options.rangeEnds, slices);
  if (ends < 2) return {};
  DepthOptions depthOptions;
  depthOptions.disparityMin = slopes.front();
  depthOptions.disparityMax = slopes.back();
  LFCAM_ASSIGN_OR_RETURN(auto estimated, estimateDepth(lightField, depthOptions));
  const auto depth = std::make_shared<const Image>(std::move(estimated.disparity));
  report(0.5);
  nlohmann::json stops = nlohmann::json::array(), ranges = nlohmann::json::array();
  for (int i = 0; i < ends; ++i) stops.push_back(int(std::lround(double(i) * (slices - 1) / (ends - 1))));
  for (int far = 0; far < ends; ++far)
    for (int near = far + 1; near < ends; ++near) {
      const double farSlope = slopes[stops[far].get<int>()], nearSlope = slopes[stops[near].get<int>()];
      LFCAM_ASSIGN_OR_RETURN(
          auto range, requestedPhoto(lightField, {{"focus-range", exact(nearSlope) + ":" + exact(farSlope)}}, depth,
                                     options.jpegQuality));
      range["far"] = far;
      range["near"] = near;
      ranges.push_back(std::move(range));
      report(0.5 + 0.5 * double(ranges.size()) / (ends * (ends - 1) / 2));
    }
  data["rangeStops"] = std::move(stops);
  data["ranges"] = std::move(ranges);
  return {};
}

}  // namespace

Result<std::string> makeLivingPicture(const LightField& lightField, const LivingPictureOptions& options,
                                      const ProgressCallback& progress) {
  if (lightField.empty()) return makeError(ErrorCode::Usage, "export-html: empty light field");
  if (options.maxSlices < 2 || options.maxSlices > 255 || options.sweepFrames < 1 || options.sweepFrames > 360 ||
      options.jpegQuality < 1 || options.jpegQuality > 100 || options.rangeEnds == 1 || options.rangeEnds < 0 ||
      options.rangeEnds > kMaxRangeEnds)
    return makeError(ErrorCode::Usage,
                     "export-html: slices must be in 2..255, frames in 1..360, quality in 1..100, "
                     "range ends 0 or 2.." +
                         std::to_string(kMaxRangeEnds));
  auto report = [&](double fraction) {
    if (progress) progress(fraction);
  };
  const int width = lightField.ns(), height = lightField.nt();

  // The labels of the all-in-focus photograph say which slice is sharpest at each pixel.
  AllInFocusOptions focusOptions;
  focusOptions.maxSlices = options.maxSlices;
  LFCAM_ASSIGN_OR_RETURN(auto composite, allInFocus(lightField, focusOptions));
  report(0.4);
  const std::vector<double>& slopes = composite.slopes;
  std::string index(std::size_t(width) * height, '\0');
  const float* labelSlope = composite.slope.plane(0);
  for (std::size_t i = 0; i < index.size(); ++i) {
    const auto nearest = std::lower_bound(slopes.begin(), slopes.end(), double(labelSlope[i]) - 1e-6);
    index[i] = char(std::min<std::ptrdiff_t>(nearest - slopes.begin(), std::ptrdiff_t(slopes.size()) - 1));
  }

  nlohmann::json data = {{"title", options.title}, {"width", width},        {"height", height},
                         {"nu", lightField.nu()},  {"nv", lightField.nv()}, {"index", base64Encode(index)}};
  data["openingSlice"] = openingSlice(width, height, int(slopes.size()), [&](int x, int y) {
    return int(std::uint8_t(index[std::size_t(y) * width + x]));
  });
  LFCAM_ASSIGN_OR_RETURN(auto allInFocusUrl, dataUrl(composite.photo, options.jpegQuality));
  data["allInFocus"] = allInFocusUrl;

  // The focal stack through the full aperture and, when asked, through a small one (more depth of
  // field, as stopping a lens down gives).
  const int stacks = options.smallAperture ? 2 : 1;
  for (int stack = 0; stack < stacks; ++stack) {
    nlohmann::json slices = nlohmann::json::array();
    for (std::size_t i = 0; i < slopes.size(); ++i) {
      std::vector<std::pair<std::string, std::string>> fields{{"slope", exact(slopes[i])}};
      if (stack == 1) fields.emplace_back("aperture", exact(smallApertureRadius(lightField)));
      LFCAM_ASSIGN_OR_RETURN(auto slice, requestedPhoto(lightField, fields, nullptr, options.jpegQuality));
      slice["slope"] = slopes[i];
      slices.push_back(std::move(slice));
      report(0.4 + 0.4 * (stack * slopes.size() + i + 1) / double(stacks * slopes.size()));
    }
    data[stack == 0 ? "slices" : "smallApertureSlices"] = std::move(slices);
  }
  if (options.smallAperture) data["smallApertureRadius"] = smallApertureRadius(lightField);

  // Pinhole viewpoints on a circle at 80% of the lens radius (Figure 7's multi-perspective
  // views when the circle leaves the lens's corners).
  nlohmann::json sweep = nlohmann::json::array();
  const double ru = 0.4 * (lightField.nu() - 1), rv = 0.4 * (lightField.nv() - 1);
  for (int k = 0; k < options.sweepFrames; ++k) {
    const double angle = 2 * std::numbers::pi * k / options.sweepFrames;
    const double u = ru * std::cos(angle), v = rv * std::sin(angle);
    LFCAM_ASSIGN_OR_RETURN(
        auto view,
        requestedPhoto(
            lightField,
            {{"slope", "0"}, {"aperture", "0"}, {"aperture-centre", exact(u) + "," + exact(v)}, {"clamp", "true"}},
            nullptr, options.jpegQuality));
    view["u"] = u;
    view["v"] = v;
    sweep.push_back(std::move(view));
    report(0.8 + 0.1 * (k + 1) / options.sweepFrames);
  }
  data["sweep"] = std::move(sweep);
  LFCAM_TRY(addFocusRanges(
      lightField, slopes, options, [&](double f) { report(0.9 + 0.1 * f); }, data));
  return pageWithData(data);
}

Status writeLivingPicture(const std::filesystem::path& output, const LightField& lightField,
                          const LivingPictureOptions& options, const ProgressCallback& progress) {
  LFCAM_ASSIGN_OR_RETURN(const std::string html, makeLivingPicture(lightField, options, progress));
  return writePage(output, html);
}

Result<std::string> makeLytroLivingPicture(const LytroRefocusStack& stack, const std::string& title) {
  if (stack.slices.size() < 2 || stack.slices.size() > 255)
    return makeError(ErrorCode::Usage, "export-html: a refocus stack of 2 to 255 slices is needed");
  nlohmann::json slices = nlohmann::json::array();
  for (const LytroRefocusSlice& slice : stack.slices)
    slices.push_back(
        {{"lambda", slice.lambda},
         {"image", "data:image/jpeg;base64," + base64Encode(std::string(slice.jpeg.begin(), slice.jpeg.end()))}});
  std::vector<double> lambdas;
  for (const LytroRefocusSlice& slice : stack.slices) lambdas.push_back(slice.lambda);
  const int width = std::max(stack.depth.width(), 1), height = std::max(stack.depth.height(), 1);
  const std::vector<double> positions = slicePositions(lambdas, stack.depth);
  // Without a depth map, the middle slice.
  const int opening = stack.depth.empty() ? int(stack.slices.size()) / 2
                                          : openingSlice(width, height, int(stack.slices.size()), [&](int x, int y) {
                                              return int(std::lround(positions[std::size_t(y) * width + x]));
                                            });
  char caption[160];
  std::snprintf(caption, sizeof caption, "a Lytro refocus stack of %zu slices, lambda %.2f to %.2f%s",
                stack.slices.size(), stack.slices.front().lambda, stack.slices.back().lambda,
                stack.depth.empty() ? " (no depth map: use the slider)" : "");
  nlohmann::json data = {{"title", title},         {"caption", caption},          {"width", width},
                         {"height", height},       {"slices", std::move(slices)}, {"sweep", nlohmann::json::array()},
                         {"openingSlice", opening}};
  if (!stack.depth.empty()) data["positions"] = std::move(positions);
  return pageWithData(data);
}

Status writeLytroLivingPicture(const std::filesystem::path& output, const LytroRefocusStack& stack,
                               const std::string& title) {
  LFCAM_ASSIGN_OR_RETURN(const std::string html, makeLytroLivingPicture(stack, title));
  return writePage(output, html);
}

}  // namespace lfcam
