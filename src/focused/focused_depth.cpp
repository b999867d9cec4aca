// Virtual depth by the micro-images' agreement: a cost volume over disparity labels on the
// photograph's frame, a box window, the least cost refined by a parabola, then confident pixels
// filling the rest.
#include "lfcam/focused/focused_depth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/box_filter.hpp"
#include "core/parabola.hpp"
#include "core/parallel.hpp"
#include "focused/disagreement_row.hpp"
#include "focused/micro_image_views.hpp"
#include "io/io_support.hpp"
#include "lfcam/focused/photo_frame.hpp"

namespace lfcam {

namespace {

constexpr float kNoEvidence = std::numeric_limits<float>::infinity();

Image luminance(const Image& image) {
  Image grey(image.width(), image.height(), 1);
  const std::size_t n = image.planeSize();
  for (int c = 0; c < image.channels(); ++c) {
    const float* in = image.plane(c);
    for (std::size_t k = 0; k < n; ++k) grey.pixels()[k] += in[k] / float(image.channels());
  }
  return grey;
}

// Unconfident pixels take the median of the confident ones in a growing window.
void fillUnconfident(Image& depth, const Image& confidence, double minConfidence) {
  const int w = depth.width(), h = depth.height();
  Image filled = depth.copy();
  parallelFor(0, std::size_t(h), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> local;
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < w; ++x) {
        if (confidence.at(x, int(y), 0) >= minConfidence) continue;
        for (int r = 2; r <= std::max(w, h); r *= 2) {
          local.clear();
          for (int yy = std::max(0, int(y) - r); yy <= std::min(h - 1, int(y) + r); ++yy)
            for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx)
              if (confidence.at(xx, yy, 0) >= minConfidence) local.push_back(depth.at(xx, yy, 0));
          if (local.size() >= 3) {
            std::nth_element(local.begin(), local.begin() + local.size() / 2, local.end());
            filled.at(x, int(y), 0) = local[local.size() / 2];
            break;
          }
        }
      }
  });
  depth = std::move(filled);
}

}  // namespace

Result<FocusedDepth> estimateFocusedDepth(const Image& image, const FocusedCalibration& calibration,
                                          const FocusedDepthRequest& request) {
  LFCAM_TRY(focused_detail::checkImageSize(image, calibration));
  const double maxVirtualDepth = request.maxVirtualDepth > 0 ? request.maxVirtualDepth : calibration.diameterPx();
  if (!(request.minVirtualDepth >= 1 && maxVirtualDepth > request.minVirtualDepth && maxVirtualDepth <= 1000))
    return makeError(ErrorCode::Usage, "virtual depth range: expected 1 <= min < max <= 1000");
  if (!(request.disparityStepPx > 0.01) || !(request.pixelsPerLens >= 1) ||
      request.pixelsPerLens > calibration.diameterPx() || request.windowRadius < 0)
    return makeError(ErrorCode::Usage,
                     "depth: a disparity step over 0.01 px, pixels per lens in [1, D] and a window "
                     "radius of at least 0 are needed");
  const double d = calibration.diameterPx();
  // Labels evenly spaced in disparity D / v, from the farthest-apart views (small v) down.
  std::vector<double> labels;
  for (double disparity = d / request.minVirtualDepth; disparity >= d / maxVirtualDepth - 1e-9;
       disparity -= request.disparityStepPx)
    labels.push_back(disparity);
  const FocusedPhotoFrame frame = focusedPhotoFrame(calibration, request.pixelsPerLens);
  const int w = frame.width, h = frame.height;
  const Image grey = luminance(image);
  const focused_detail::MicroImageViews views(calibration);
  const std::size_t plane = std::size_t(w) * std::size_t(h);
  // Every element is written before it is read: left uninitialised rather than zeroed page by page.
  const std::unique_ptr<float[]> cost(new float[labels.size() * plane]);

  parallelFor(0, labels.size(), 1, [&](std::size_t begin, std::size_t end) {
    const std::unique_ptr<float[]> raw(new float[plane]), windowed(new float[plane]), count(new float[plane]),
        countWindowed(new float[plane]);
    focused_detail::DisagreementSums sums;
    for (std::size_t l = begin; l < end; ++l) {
      const double v = d / labels[l];
      const focused_detail::LensesByRow lenses(views, frame, v * views.usableRadius(), 0, h);
      for (int py = 0; py < h; ++py)
        focused_detail::disagreementRow(grey, lenses, frame, v, calibration.orientationSign(), py, 0, w, sums,
                                        raw.get() + std::size_t(py) * w, count.get() + std::size_t(py) * w);
      boxFilter(raw.get(), windowed.get(), w, h, request.windowRadius);
      boxFilter(count.get(), countWindowed.get(), w, h, request.windowRadius);
      float* out = cost.get() + l * plane;
      for (std::size_t k = 0; k < plane; ++k)
        out[k] = countWindowed[k] > 0.5f ? windowed[k] / countWindowed[k] : kNoEvidence;
    }
  });

  FocusedDepth result{Image(w, h, 1), Image(w, h, 1), {}};
  // The least cost per pixel; confidence 1 - least / greatest (how much worse the other labels are).
  parallelFor(0, std::size_t(h), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t py = begin; py < end; ++py)
      for (int px = 0; px < w; ++px) {
        const std::size_t k = py * std::size_t(w) + px;
        std::size_t best = 0;
        float bestCost = kNoEvidence, worst = 0;
        for (std::size_t l = 0; l < labels.size(); ++l) {
          const float c = cost[l * plane + k];
          if (c < bestCost) {
            bestCost = c;
            best = l;
          }
          if (c != kNoEvidence) worst = std::max(worst, c);
        }
        if (bestCost == kNoEvidence) {
          result.virtualDepth.at(px, int(py), 0) = float(maxVirtualDepth);
          continue;
        }
        double disparity = labels[best];
        if (best > 0 && best + 1 < labels.size() && cost[(best - 1) * plane + k] != kNoEvidence &&
            cost[(best + 1) * plane + k] != kNoEvidence) {
          const double offset = parabolaVertex(cost[(best - 1) * plane + k], bestCost, cost[(best + 1) * plane + k]);
          disparity -= offset * request.disparityStepPx;
        }
        result.virtualDepth.at(px, int(py), 0) = float(d / disparity);
        result.confidence.at(px, int(py), 0) = worst > 0 ? float(1 - bestCost / worst) : 0.0f;
      }
  });
  fillUnconfident(result.virtualDepth, result.confidence, request.minConfidence);

  // Per micro-image: the median over the pixels nearest its centre.
  const LensletGrid& grid = calibration.grid;
  result.lensVirtualDepth.assign(std::size_t(grid.columns) * grid.rows, 0.0f);
  std::vector<std::vector<float>> seen(result.lensVirtualDepth.size());
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const auto q = frame.imagePoint(px + 0.5, py + 0.5);
      const auto [i, j] = views.nearestLens(q[0], q[1]);
      if (i >= 0) seen[std::size_t(j) * grid.columns + i].push_back(result.virtualDepth.at(px, py, 0));
    }
  for (std::size_t k = 0; k < seen.size(); ++k)
    if (!seen[k].empty()) {
      std::nth_element(seen[k].begin(), seen[k].begin() + seen[k].size() / 2, seen[k].end());
      result.lensVirtualDepth[k] = seen[k][seen[k].size() / 2];
    }
  return result;
}

}  // namespace lfcam
