// The photograph of a focused plenoptic image: scalar rendering, one pixel at a time.
#include "lfcam/focused/focused_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/bilinear.hpp"
#include "core/cubic.hpp"
#include "core/parallel.hpp"
#include "focused/micro_image_views.hpp"
#include "io/io_support.hpp"
#include "lfcam/focused/focused_depth.hpp"

namespace lfcam {

namespace {

// Keys's a: sharper than Catmull-Rom, it offsets part of the sensor pixel's blur (docs/design.md).
constexpr double kKeysA = -0.75;
// That suits photograph pixels up to about 1.3 sensor pixels of the micro-image; from 2 bilinear,
// whose low pass a wider footprint wants, does better (3-9 dB at 2.2-3.2 px); a blend between.
constexpr double kSharpUpToPx = 1.3, kBilinearFromPx = 2.0;
// A lens type's weight at v: exp(-(blur / kBlurScalePx)^2), its defocus blur D |1/v - 1/v_t| pixels
// (thin lenses: the microlens's aperture is D pixels, v_t the middle of its sharp range in 1/v).
constexpr double kBlurScalePx = 0.75;
// Types weighted less than this share of the sharpest are not sampled.
constexpr double kLeastTypeWeight = 0.01;

}  // namespace

Result<Image> renderFocused(const Image& image, const FocusedCalibration& calibration,
                            const FocusedRenderRequest& request) {
  LFCAM_TRY(focused_detail::checkImageSize(image, calibration));
  if (!(request.pixelsPerLens >= 1 && request.pixelsPerLens <= calibration.diameterPx()))
    return makeError(ErrorCode::Usage, "pixels per lens must be in [1, " +
                                           io::shortestNumber(calibration.diameterPx()) +
                                           "] (the micro-image diameter)");
  const double diameter = calibration.diameterPx(), usable = 0.5 * diameter - calibration.borderPx;
  const double shift = std::hypot(request.viewpoint[0], request.viewpoint[1]);
  if (!(request.aperture > 0 && request.aperture + shift <= 1 + 1e-9))
    return makeError(ErrorCode::Usage, "the aperture (" + io::shortestNumber(request.aperture) +
                                           ") and the viewpoint's distance from the centre (" +
                                           io::shortestNumber(shift) + ") must add up to at most 1");
  const FocusedPhotoFrame frame = focusedPhotoFrame(calibration, request.pixelsPerLens);
  if (request.virtualDepthMap &&
      (request.virtualDepthMap->width() != frame.width || request.virtualDepthMap->height() != frame.height))
    return makeError(ErrorCode::Usage, "the virtual depth map is " + std::to_string(request.virtualDepthMap->width()) +
                                           "x" + std::to_string(request.virtualDepthMap->height()) +
                                           ", the photograph " + std::to_string(frame.width) + "x" +
                                           std::to_string(frame.height));
  if (!request.virtualDepthMap && !(request.virtualDepth > 0 && std::isfinite(request.virtualDepth)))
    return makeError(ErrorCode::Usage, "the virtual depth must be positive");
  if (request.nearestLensOnly && !request.virtualDepthMap) {
    // The farthest point of a lattice cell from its centre, over v, must stay on the micro-image.
    const double cellRadius = calibration.grid.packing == Packing::Hexagonal
                                  ? calibration.diameterPx() / std::sqrt(3.0)
                                  : calibration.diameterPx() / std::sqrt(2.0);
    if (cellRadius / request.virtualDepth > usable)
      return makeError(ErrorCode::Usage, "virtual depth " + io::shortestNumber(request.virtualDepth) +
                                             ": its patches would reach past the micro-images; at least " +
                                             io::shortestNumber(std::ceil(cellRadius / usable * 100) / 100) +
                                             " is needed");
  }

  const focused_detail::MicroImageViews views(calibration, request.aperture, request.viewpoint);
  const int channels = image.channels();
  Image photo(frame.width, frame.height, channels);
  // Each lens's type, looked up once rather than at every visit.
  const LensletGrid& grid = calibration.grid;
  std::vector<int> typeOfLens(std::size_t(grid.columns) * std::size_t(grid.rows));
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i)
      typeOfLens[std::size_t(j) * std::size_t(grid.columns) + std::size_t(i)] = calibration.lensType(i, j);
  // Each type's 1/v_t, and whether types are weighted by their sharpness at all.
  std::vector<double> inverseFocus;
  for (const LensType& type : calibration.lensTypes)
    inverseFocus.push_back(0.5 * (1 / type.minVirtualDepth + 1 / type.maxVirtualDepth));
  const bool weighTypes = request.sharpLensTypes && calibration.lensTypes.size() > 1;

  parallelFor(0, std::size_t(frame.height), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<double> sum(static_cast<std::size_t>(channels));
    std::vector<double> typeWeight(calibration.lensTypes.size(), 1.0);
    for (std::size_t py = begin; py < end; ++py)
      for (int px = 0; px < frame.width; ++px) {
        const auto q = frame.imagePoint(px + 0.5, py + 0.5);
        const double v = request.virtualDepthMap ? request.virtualDepthMap->at(px, int(py), 0) : request.virtualDepth;
        std::fill(sum.begin(), sum.end(), 0.0);
        double total = 0;
        // A photograph pixel's width in the micro-image's pixels: the pitch over pixelsPerLens, over v.
        const double footprint = diameter / (request.pixelsPerLens * v);
        const double bilinearShare =
            std::clamp((footprint - kSharpUpToPx) / (kBilinearFromPx - kSharpUpToPx), 0.0, 1.0);
        auto add = [&](const focused_detail::MicroImageSample& s, double weight) {
          for (int c = 0; c < channels; ++c) {
            const float* plane = image.plane(c);
            const double x = s.x - 0.5, y = s.y - 0.5;
            double value = 0;
            if (bilinearShare < 1)
              value += (1 - bilinearShare) * cubicSample(plane, image.width(), image.height(), x, y, kKeysA);
            if (bilinearShare > 0) value += bilinearShare * bilinearSample(plane, image.width(), image.height(), x, y);
            sum[std::size_t(c)] += weight * value;
          }
          total += weight;
        };
        if (v > 0 && std::isfinite(v)) {
          if (weighTypes) {
            // exp(-blur^2 / scale^2) over the sharpest type's: the types' weights relative to its.
            double least = std::numeric_limits<double>::infinity();
            for (std::size_t t = 0; t < typeWeight.size(); ++t) {
              typeWeight[t] = std::pow(diameter * (1 / v - inverseFocus[t]) / kBlurScalePx, 2);
              least = std::min(least, typeWeight[t]);
            }
            for (double& w : typeWeight) {
              w = std::exp(least - w);
              if (w < kLeastTypeWeight) w = 0;
            }
          }
          const auto nearest = views.forEach(q[0], q[1], v, [&](const focused_detail::MicroImageSample& s) {
            if (request.nearestLensOnly) return;
            const double type =
                typeWeight[std::size_t(typeOfLens[std::size_t(s.j) * std::size_t(grid.columns) + std::size_t(s.i)])];
            if (type == 0) return;
            const double w = 1 - s.rho * s.rho;  // smoothly to 0 at the disc's rim: no seams
            add(s, type * w * w);
          });
          // Basic rendering, or no disc holds S: the micro-image nearest it.
          if (total == 0 && nearest.i >= 0) add(nearest, 1);
        }
        for (int c = 0; c < channels; ++c)
          photo.at(px, int(py), c) = total > 0 ? float(sum[std::size_t(c)] / total) : 0.0f;
      }
  });
  return photo;
}

Result<Image> renderTotalFocus(const Image& image, const FocusedCalibration& calibration, double pixelsPerLens,
                               const Image* virtualDepthMap) {
  FocusedRenderRequest request;
  request.pixelsPerLens = pixelsPerLens;
  request.virtualDepthMap = virtualDepthMap;
  if (virtualDepthMap) return renderFocused(image, calibration, request);
  FocusedDepthRequest depthRequest;
  depthRequest.pixelsPerLens = pixelsPerLens;
  LFCAM_ASSIGN_OR_RETURN(const FocusedDepth depth, estimateFocusedDepth(image, calibration, depthRequest));
  request.virtualDepthMap = &depth.virtualDepth;
  return renderFocused(image, calibration, request);
}

}  // namespace lfcam
