// Virtual depth by the micro-images' agreement: a cost per disparity label on the photograph's
// frame over a box window, the least cost per pixel refined by a parabola, then confident pixels
// filling the rest; coarse to fine over frames of fewer pixels per lens. Rows go in bands, each
// through its labels, keeping only what the least cost needs rather than the whole cost volume.
#include "lfcam/focused/focused_depth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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
// Rows a task takes through the labels: the window's rows above and below are costed again.
constexpr int kBandRows = 32;
// Columns of a row between two runs that are costed anyway: fewer than going through the row's
// lenses once more.
constexpr int kRunGap = 16;
// The coarse-to-fine search (searchPyramid): its frames have at least this many pixels per lens,
constexpr double kLeastPixelsPerLens = 1;
constexpr int kCoarsestStride = 2;  // the coarsest searches every other label,
constexpr int kMargin = 2;          // a finer one that many either side of the coarse labels near
                                    // (one when those came from every label),
constexpr float kAgreement = 1;     // or none where those are within one label of each other.

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

// Labels [first, last] (none when last < first).
struct LabelRange {
  int first = 0, last = -1;
};

// The labels a pixel searches: one range, or two far apart (the two sides of a depth edge).
struct LabelSet {
  LabelRange low, high;
  bool holds(int l) const { return (l >= low.first && l <= low.last) || (l >= high.first && l <= high.last); }
};

// Per pixel: the label of least cost (a fractional index, refined by a parabola when both
// neighbours were costed; -1 without evidence), that cost, and the greatest finite cost seen.
struct LabelSearch {
  std::vector<float> label, least, worst;
};

// The least windowed cost of each pixel of `frame` over its labels (sets, row-major), taken in
// increasing order within a band of rows, so that the least, its neighbours and the greatest are
// kept as they come. Pixels with no labels keep `start`'s values; the others start from its worst
// (their cost beyond their labels, when known), label -1 and least kNoEvidence.
LabelSearch searchLabels(const Image& grey, const FocusedCalibration& calibration,
                         const focused_detail::MicroImageViews& views, const FocusedPhotoFrame& frame,
                         const std::vector<double>& labels, int radius, const std::vector<LabelSet>& sets,
                         LabelSearch start) {
  const int w = frame.width, h = frame.height, count = int(labels.size());
  const double d = calibration.diameterPx();
  LabelSearch result = std::move(start);
  const std::size_t bands = std::size_t((h + kBandRows - 1) / kBandRows);
  parallelFor(0, bands, 1, [&](std::size_t bandBegin, std::size_t bandEnd) {
    std::vector<float> raw, seen, windowed, seenWindowed, before, after, last;
    std::vector<LabelRange> columns;
    std::vector<unsigned char> searching, reached;
    std::vector<int> best;
    focused_detail::DisagreementSums sums;
    for (std::size_t band = bandBegin; band < bandEnd; ++band) {
      const int y0 = int(band) * kBandRows, y1 = std::min(h, y0 + kBandRows);
      const std::size_t pixels = std::size_t(y1 - y0) * std::size_t(w), first = std::size_t(y0) * std::size_t(w);
      // The columns of each band row (less y0) that search each label: [y * count + l].
      columns.assign(std::size_t(y1 - y0) * std::size_t(count), LabelRange{w, -1});
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
          const LabelSet& set = sets[std::size_t(y) * std::size_t(w) + std::size_t(x)];
          for (const LabelRange& r : {set.low, set.high})
            for (int l = r.first; l <= r.last; ++l) {
              LabelRange& c = columns[std::size_t(y - y0) * std::size_t(count) + std::size_t(l)];
              c = {std::min(c.first, x), std::max(c.last, x)};
            }
        }
      searching.assign(pixels, 0);
      best.assign(pixels, -1);
      before.assign(pixels, kNoEvidence);
      after.assign(pixels, kNoEvidence);
      last.assign(pixels, kNoEvidence);
      for (int l = 0; l < count; ++l) {
        const auto columnsOf = [&](int y) {
          return columns[std::size_t(y - y0) * std::size_t(count) + std::size_t(l)];
        };
        int rowFirst = y1, rowLast = -1, left = w, right = -1;
        for (int y = y0; y < y1; ++y)
          if (const LabelRange c = columnsOf(y); c.first <= c.last) {
            rowFirst = std::min(rowFirst, y);
            rowLast = y;
            left = std::min(left, c.first);
            right = std::max(right, c.last);
          }
        if (rowLast < 0) continue;
        // The costs those pixels' windows reach, on rows [ya, yb) and columns [xa, xb).
        const int ya = std::max(0, rowFirst - radius), yb = std::min(h, rowLast + radius + 1);
        const int xa = std::max(0, left - radius), xb = std::min(w, right + radius + 1);
        const std::size_t bw = std::size_t(xb - xa), area = bw * std::size_t(yb - ya);
        raw.assign(area, 0.0f);
        seen.assign(area, 0.0f);
        windowed.resize(area);
        seenWindowed.resize(area);
        const double v = d / labels[std::size_t(l)];
        const focused_detail::LensesByRow lenses(views, frame, v * views.usableRadius(), ya, yb);
        // Which pixels of the band search l; then on each row [ya, yb) the runs of columns their
        // windows reach (the two sides of a card, say, rather than all between).
        for (int y = rowFirst; y <= rowLast; ++y)
          for (int x = columnsOf(y).first; x <= columnsOf(y).last; ++x) {
            const std::size_t k = std::size_t(y - y0) * std::size_t(w) + std::size_t(x);
            searching[k] = sets[first + k].holds(l);
          }
        for (int yy = ya; yy < yb; ++yy) {
          reached.assign(std::size_t(xb - xa), 0);
          for (int y = std::max(y0, yy - radius); y <= std::min(y1 - 1, yy + radius); ++y)
            for (int x = columnsOf(y).first; x <= columnsOf(y).last; ++x)
              reached[std::size_t(x - xa)] |= searching[std::size_t(y - y0) * std::size_t(w) + std::size_t(x)];
          for (int x = xa; x < xb;) {
            if (!reached[std::size_t(x - xa)]) {
              ++x;
              continue;
            }
            // Runs closer than kRunGap beyond the windows' reach go together.
            int lastReached = x, next = x + 1;
            for (; next < xb && next <= lastReached + 2 * radius + kRunGap; ++next)
              if (reached[std::size_t(next - xa)]) lastReached = next;
            const int begin = std::max(xa, x - radius), end = std::min(xb, lastReached + radius + 1);
            const std::size_t at = std::size_t(yy - ya) * bw + std::size_t(begin - xa);
            focused_detail::disagreementRow(grey, lenses, frame, v, calibration.orientationSign(), yy, begin, end, sums,
                                            raw.data() + at, seen.data() + at);
            x = next;
          }
        }
        for (int y = rowFirst; y <= rowLast; ++y)
          for (int x = columnsOf(y).first; x <= columnsOf(y).last; ++x)
            searching[std::size_t(y - y0) * std::size_t(w) + std::size_t(x)] = 0;
        boxFilter(raw.data(), windowed.data(), xb - xa, yb - ya, radius);
        boxFilter(seen.data(), seenWindowed.data(), xb - xa, yb - ya, radius);
        for (int y = rowFirst; y <= rowLast; ++y) {
          const LabelRange c = columnsOf(y);
          for (int x = c.first; x <= c.last; ++x) {
            const std::size_t k = std::size_t(y - y0) * std::size_t(w) + std::size_t(x);
            if (!sets[first + k].holds(l)) continue;
            const std::size_t at = std::size_t(y - ya) * bw + std::size_t(x - xa);
            const float cost = seenWindowed[at] > 0.5f ? windowed[at] / seenWindowed[at] : kNoEvidence;
            float& least = result.least[first + k];
            if (cost < least) {
              least = cost;
              best[k] = l;
              before[k] = sets[first + k].holds(l - 1) ? last[k] : kNoEvidence;
              after[k] = kNoEvidence;
            } else if (l == best[k] + 1) {
              after[k] = cost;
            }
            last[k] = cost;
            if (cost != kNoEvidence) result.worst[first + k] = std::max(result.worst[first + k], cost);
          }
        }
      }
      for (std::size_t k = 0; k < pixels; ++k) {
        if (best[k] < 0) continue;
        const bool curve = before[k] != kNoEvidence && after[k] != kNoEvidence;
        result.label[first + k] =
            float(best[k] + (curve ? parabolaVertex(before[k], result.least[first + k], after[k]) : 0.0));
      }
    }
  });
  return result;
}

// Whether the frame of `pixelsPerLens` is searched after one of half the pixels per lens.
bool refinesCoarser(const FocusedCalibration& calibration, double pixelsPerLens) {
  const FocusedPhotoFrame coarse = focusedPhotoFrame(calibration, pixelsPerLens / 2);
  return pixelsPerLens / 2 >= kLeastPixelsPerLens && coarse.width >= 2 && coarse.height >= 2;
}

// searchLabels on the frame of `pixelsPerLens`. When it refines a coarser frame's search (a
// quarter of the pixels), each pixel searches only around the least and the greatest label its
// 3x3 nearest coarse pixels found (and between them when near), kMargin either side, or 1 when
// those searched every label; their nearest one's greatest cost stands for the labels left out.
// Where they agree within kAgreement, having searched every label, it takes their labels
// interpolated and searches none: it searches at depth edges. The coarsest frame searches every
// kCoarsestStride-th label, or every label when it is the one asked for (`refined` false).
LabelSearch searchPyramid(const Image& grey, const FocusedCalibration& calibration,
                          const focused_detail::MicroImageViews& views, double pixelsPerLens,
                          const std::vector<double>& labels, int radius, bool refined) {
  const FocusedPhotoFrame frame = focusedPhotoFrame(calibration, pixelsPerLens),
                          coarse = focusedPhotoFrame(calibration, pixelsPerLens / 2);
  const int w = frame.width, h = frame.height, last = int(labels.size()) - 1;
  const std::size_t plane = std::size_t(w) * std::size_t(h);
  LabelSearch start{std::vector<float>(plane, -1.0f), std::vector<float>(plane, kNoEvidence),
                    std::vector<float>(plane, 0.0f)};
  if (!refinesCoarser(calibration, pixelsPerLens)) {
    const int stride = refined ? kCoarsestStride : 1;
    std::vector<double> sparse;
    for (std::size_t l = 0; l < labels.size(); l += std::size_t(stride)) sparse.push_back(labels[l]);
    LabelSearch found = searchLabels(grey, calibration, views, frame, sparse, radius,
                                     std::vector<LabelSet>(plane, {{0, int(sparse.size()) - 1}, {}}), std::move(start));
    for (float& l : found.label)
      if (l >= 0) l *= float(stride);
    return found;
  }
  const LabelSearch found = searchPyramid(grey, calibration, views, pixelsPerLens / 2, labels, radius, true);
  const bool everyLabel = refinesCoarser(calibration, pixelsPerLens / 2);
  std::vector<LabelSet> sets(plane);
  parallelFor(0, std::size_t(h), 1, [&](std::size_t begin, std::size_t end) {
    const auto coarseAt = [&](const std::vector<float>& values, int x, int y) {
      return values[std::size_t(y) * std::size_t(coarse.width) + std::size_t(x)];
    };
    for (std::size_t py = begin; py < end; ++py)
      for (int px = 0; px < w; ++px) {
        const std::size_t k = py * std::size_t(w) + std::size_t(px);
        const auto q = frame.imagePoint(px + 0.5, double(py) + 0.5);
        const double fx =
            std::clamp((q[0] - coarse.originPx[0]) / coarse.imagePxPerPixel - 0.5, 0.0, coarse.width - 1.0);
        const double fy =
            std::clamp((q[1] - coarse.originPx[1]) / coarse.imagePxPerPixel - 0.5, 0.0, coarse.height - 1.0);
        const int cx = int(std::lround(fx)), cy = int(std::lround(fy));
        start.worst[k] = coarseAt(found.worst, cx, cy);
        float least = float(last + 1), greatest = -1;
        bool all = true;
        for (int y = std::max(0, cy - 1); y <= std::min(coarse.height - 1, cy + 1); ++y)
          for (int x = std::max(0, cx - 1); x <= std::min(coarse.width - 1, cx + 1); ++x) {
            const float l = coarseAt(found.label, x, y);
            all &= l >= 0;
            if (l >= 0) {
              least = std::min(least, l);
              greatest = std::max(greatest, l);
            }
          }
        if (everyLabel && all && greatest - least <= kAgreement) {
          const int x0 = std::min(int(fx), coarse.width - 2), y0 = std::min(int(fy), coarse.height - 2);
          const double ax = fx - x0, ay = fy - y0;
          const auto row = [&](int y) {
            return (1 - ax) * coarseAt(found.label, x0, y) + ax * coarseAt(found.label, x0 + 1, y);
          };
          start.label[k] = float((1 - ay) * row(y0) + ay * row(y0 + 1));
          start.least[k] = coarseAt(found.least, cx, cy);
        } else if (greatest >= 0) {
          // Around the least and the greatest, not all labels between: an edge's two sides.
          const int low = int(std::lround(least)), high = int(std::lround(greatest));
          const int margin = everyLabel ? 1 : kMargin;
          const LabelRange around{std::max(0, low - margin), std::min(last, low + margin)};
          if (high - low <= 2 * margin + 1)
            sets[k].low = {around.first, std::min(last, high + margin)};
          else
            sets[k] = {around, {high - margin, std::min(last, high + margin)}};
        } else {
          sets[k].low = {0, last};
        }
      }
  });
  return searchLabels(grey, calibration, views, frame, labels, radius, sets, std::move(start));
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
  const std::size_t plane = std::size_t(w) * std::size_t(h);
  const focused_detail::MicroImageViews views(calibration);
  // A one-channel image is its own luminance, not copied.
  Image mixed;
  const Image& grey = image.channels() == 1 ? image : (mixed = luminance(image));
  const LabelSearch search =
      searchPyramid(grey, calibration, views, request.pixelsPerLens, labels, request.windowRadius, false);
  FocusedDepth result{Image(w, h, 1), Image(w, h, 1), {}};
  // Confidence 1 - least / greatest: how much worse the other labels are.
  for (std::size_t k = 0; k < plane; ++k) {
    if (search.label[k] < 0) {
      result.virtualDepth.pixels()[k] = float(maxVirtualDepth);
      continue;
    }
    result.virtualDepth.pixels()[k] = float(d / (labels[0] - search.label[k] * request.disparityStepPx));
    result.confidence.pixels()[k] = search.worst[k] > 0 ? float(1 - search.least[k] / search.worst[k]) : 0.0f;
  }
  fillUnconfident(result.virtualDepth, result.confidence, request.minConfidence);

  // Per micro-image: the median over the pixels nearest its centre.
  const LensletGrid& grid = calibration.grid;
  result.lensVirtualDepth.assign(std::size_t(grid.columns) * grid.rows, 0.0f);
  std::vector<int> nearest(plane);
  parallelFor(0, std::size_t(h), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t py = begin; py < end; ++py)
      for (int px = 0; px < w; ++px) {
        const auto q = frame.imagePoint(px + 0.5, double(py) + 0.5);
        const auto [i, j] = views.nearestLens(q[0], q[1]);
        nearest[py * std::size_t(w) + std::size_t(px)] = i < 0 ? -1 : j * grid.columns + i;
      }
  });
  std::vector<std::vector<float>> seen(result.lensVirtualDepth.size());
  for (std::size_t k = 0; k < plane; ++k)
    if (nearest[k] >= 0) seen[std::size_t(nearest[k])].push_back(result.virtualDepth.pixels()[k]);
  for (std::size_t k = 0; k < seen.size(); ++k)
    if (!seen[k].empty()) {
      std::nth_element(seen[k].begin(), seen[k].begin() + seen[k].size() / 2, seen[k].end());
      result.lensVirtualDepth[k] = seen[k][seen[k].size() / 2];
    }
  return result;
}

}  // namespace lfcam
