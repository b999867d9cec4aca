// makeFocusedLivingPicture (living_picture.hpp): a focused plenoptic capture's page, its slices,
// total focus and viewpoints rendered from the micro-images (focused_render.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <nlohmann/json.hpp>

#include "lfcam/focused/focused_depth.hpp"
#include "lfcam/focused/focused_render.hpp"
#include "lfcam/viewer/living_picture.hpp"
#include "viewer/living_page.hpp"

namespace lfcam {

namespace {

// The virtual depths the map puts its confident pixels at, from the 2nd to the 98th percentile:
// the stack spans the scene, not the candidates' whole range.
std::array<double, 2> sceneVirtualDepths(const FocusedDepth& depth, double minConfidence) {
  std::vector<float> values;
  const auto v = depth.virtualDepth.pixels(), confidence = depth.confidence.pixels();
  for (std::size_t i = 0; i < v.size(); ++i)
    if (confidence[i] >= minConfidence && std::isfinite(v[i])) values.push_back(v[i]);
  if (values.empty()) return {2, 12};
  std::sort(values.begin(), values.end());
  const auto at = [&](double share) { return double(values[std::size_t(share * double(values.size() - 1))]); };
  const double nearest = at(0.02), farthest = std::max(at(0.98), nearest * 1.05);
  return {nearest, farthest};
}

}  // namespace

Result<std::string> makeFocusedLivingPicture(const Image& image, const FocusedCalibration& calibration,
                                             double pixelsPerLens, const LivingPictureOptions& options,
                                             const ProgressCallback& progress) {
  if (options.maxSlices < 2 || options.maxSlices > 255 || options.sweepFrames < 1 || options.sweepFrames > 360 ||
      options.jpegQuality < 1 || options.jpegQuality > 100)
    return makeError(ErrorCode::Usage, "export-html: slices must be in 2..255, frames in 1..360, quality in 1..100");
  auto report = [&](double fraction) {
    if (progress) progress(fraction);
  };
  FocusedDepthRequest depthRequest;
  depthRequest.pixelsPerLens = pixelsPerLens;
  LFCAM_ASSIGN_OR_RETURN(const FocusedDepth depth, estimateFocusedDepth(image, calibration, depthRequest));
  report(0.4);
  const int width = depth.virtualDepth.width(), height = depth.virtualDepth.height();
  FocusedRenderRequest request;
  request.pixelsPerLens = pixelsPerLens;

  // Slices evenly spaced in 1 / v (in disparity, as a lens's focus moves), by increasing v.
  const auto [nearV, farV] = sceneVirtualDepths(depth, depthRequest.minConfidence);
  const int count = options.maxSlices;
  std::vector<double> virtualDepths;
  for (int i = 0; i < count; ++i) virtualDepths.push_back(1 / (1 / nearV + (1 / farV - 1 / nearV) * i / (count - 1)));
  nlohmann::json slices = nlohmann::json::array();
  for (int i = 0; i < count; ++i) {
    request.virtualDepth = virtualDepths[std::size_t(i)];
    LFCAM_ASSIGN_OR_RETURN(auto photo, renderFocused(image, calibration, request));
    LFCAM_ASSIGN_OR_RETURN(auto url, dataUrl(photo, options.jpegQuality));
    slices.push_back({{"virtualDepth", virtualDepths[std::size_t(i)]}, {"image", url}});
    report(0.4 + 0.3 * (i + 1) / count);
  }
  const std::vector<double> positions = slicePositions(virtualDepths, depth.virtualDepth);

  // The total focus, and viewpoints on a circle at half the usable radius through a disc of 0.3 of
  // it, each pixel at its own virtual depth.
  request.virtualDepthMap = &depth.virtualDepth;
  LFCAM_ASSIGN_OR_RETURN(auto totalFocus, renderFocused(image, calibration, request));
  LFCAM_ASSIGN_OR_RETURN(auto totalFocusUrl, dataUrl(totalFocus, options.jpegQuality));
  request.aperture = 0.3;
  nlohmann::json sweep = nlohmann::json::array();
  for (int k = 0; k < options.sweepFrames; ++k) {
    const double angle = 2 * std::numbers::pi * k / options.sweepFrames;
    request.viewpoint = {0.5 * std::cos(angle), 0.5 * std::sin(angle)};
    LFCAM_ASSIGN_OR_RETURN(auto view, renderFocused(image, calibration, request));
    LFCAM_ASSIGN_OR_RETURN(auto url, dataUrl(view, options.jpegQuality));
    sweep.push_back({{"u", request.viewpoint[0]}, {"v", request.viewpoint[1]}, {"image", url}});
    report(0.7 + 0.3 * (k + 1) / options.sweepFrames);
  }

  char caption[200];
  std::snprintf(caption, sizeof caption,
                "a focused plenoptic capture: %d slices, virtual depth %.2f to %.2f, %d x %d (%g pixels per lens)",
                count, nearV, farV, width, height, pixelsPerLens);
  nlohmann::json data = {{"title", options.title},
                         {"caption", caption},
                         {"width", width},
                         {"height", height},
                         {"slices", std::move(slices)},
                         {"positions", positions},
                         {"allInFocus", totalFocusUrl},
                         {"sweep", std::move(sweep)},
                         {"sweepUnit", "of the lens"},
                         {"openingSlice", openingSlice(width, height, count, [&](int x, int y) {
                            return int(std::lround(positions[std::size_t(y) * width + x]));
                          })}};
  return pageWithData(data);
}

Status writeFocusedLivingPicture(const std::filesystem::path& output, const Image& image,
                                 const FocusedCalibration& calibration, double pixelsPerLens,
                                 const LivingPictureOptions& options, const ProgressCallback& progress) {
  LFCAM_ASSIGN_OR_RETURN(const std::string html,
                         makeFocusedLivingPicture(image, calibration, pixelsPerLens, options, progress));
  return writePage(output, html);
}

}  // namespace lfcam
