// The image calibration measures on (calibrate_internal.hpp, docs/design.md "Calibration", step
// 1): one channel, black level off, a mosaic's 2x2 phases scaled to one mean, the 3x3 median, a
// mosaic's [1 2 1] binomial, and the [1 2 1]^2 smoothing of the centre search. The fast path
// streams each band of rows through all the steps at once (three rows per step, in cache), so an
// Illum-size image is read once and only the result is written; the reference runs each step
// over the whole image. Both make the same floats.
#include <algorithm>
#include <functional>
#include <utility>
#include <vector>

#include "calibrate/calibrate_internal.hpp"
#include "core/parallel.hpp"

namespace lfcam::calibrate_detail {

namespace {

bool isMosaic(ColorFilter filter) { return filter != ColorFilter::Mono; }

// Columns [x0, x1) of row y: the channels' mean, black level off.
void greyRow(const Image& image, int y, float black, int x0, int x1, float* out) {
  const float* first = image.row(y, 0);
  for (int x = x0; x < x1; ++x) out[x] = first[x];
  for (int c = 1; c < image.channels(); ++c) {
    const float* in = image.row(y, c);
    for (int x = x0; x < x1; ++x) out[x] += in[x];
  }
  const float channels = float(image.channels());
  for (int x = x0; x < x1; ++x) out[x] = out[x] / channels - black;
}

// The rows of one step, made on demand from the step before. Requests come in increasing order
// within three consecutive rows (a 3-row filter clamped at the borders), so three are kept.
class RowRing {
 public:
  RowRing(int width, std::function<void(int, float*)> make)
      : rows_(3 * std::size_t(width)), width_(width), make_(std::move(make)) {}
  const float* row(int y) {
    if (next_ < 0) next_ = y;
    for (; next_ <= y; ++next_) make_(next_, slot(next_));
    return slot(y);
  }

 private:
  float* slot(int y) { return rows_.data() + std::size_t(y % 3) * width_; }
  std::vector<float> rows_;
  int width_;
  std::function<void(int, float*)> make_;
  int next_ = -1;
};

// Rows [y0, y1), columns [x0, x1) of the prepared (and, if `smoothed`, smoothed) image into out
// (its row y - outY, column x - x0).
void prepareBand(const Image& image, const CalibrationOptions& options, const PhaseGains& gains, int x0, int x1, int y0,
                 int y1, bool smoothed, Image& out, int outY) {
  const int width = image.width(), height = image.height();
  const bool median = options.target != CalibrationTarget::Pinhole, binomial = isMosaic(options.colorFilter);
  // Each 3-wide step needs one more column each side than the step after it.
  const int haloWork = smoothed ? 1 : 0, haloBefore = haloWork + (binomial ? 1 : 0),
            haloGrey = haloBefore + (median ? 1 : 0);
  const auto from = [&](int halo) { return std::max(x0 - halo, 0); };
  const auto to = [&](int halo) { return std::min(x1 + halo, width); };
  const float black = float(options.blackLevel);
  RowRing grey(width, [&](int y, float* row) {
    greyRow(image, y, black, from(haloGrey), to(haloGrey), row);
    if (!binomial) return;  // a mosaic: each phase to the common mean
    const float g0 = gains.gain[2 * (y & 1)], g1 = gains.gain[2 * (y & 1) + 1];
    for (int x = from(haloGrey); x < to(haloGrey); ++x) row[x] *= x & 1 ? g1 : g0;
  });
  RowRing filtered(width, [&](int y, float* row) {
    const float* above = y > 0 ? grey.row(y - 1) : nullptr;  // in this order: the ring's requests rise
    const float* middle = grey.row(y);
    const float* below = y + 1 < height ? grey.row(y + 1) : nullptr;
    median3x3Row(above, middle, below, width, from(haloBefore), to(haloBefore), row);
  });
  RowRing& before = median ? filtered : grey;  // a pinhole's spots may be a pixel across: no median
  // The binomial along x, then along y (borders clamped).
  RowRing alongX(width, [&](int y, float* row) {
    const float* in = before.row(y);
    for (int x = from(haloWork); x < to(haloWork); ++x)
      row[x] = 0.25f * (in[std::max(x - 1, 0)] + 2 * in[x] + in[std::min(x + 1, width - 1)]);
  });
  RowRing alongY(width, [&](int y, float* row) {
    const float* above = alongX.row(std::max(y - 1, 0));
    const float* middle = alongX.row(y);
    const float* below = alongX.row(std::min(y + 1, height - 1));
    for (int x = from(haloWork); x < to(haloWork); ++x) row[x] = 0.25f * (above[x] + 2 * middle[x] + below[x]);
  });
  RowRing& work = binomial ? alongY : before;
  std::vector<float> column(smoothed ? width : 0);
  for (int y = y0; y < y1; ++y) {
    float* o = out.row(y - outY, 0);
    if (!smoothed) {
      const float* in = work.row(y);
      std::copy(in + x0, in + x1, o);
      continue;
    }
    // [1 2 1] along y into a row, then along x (borders clamped).
    const float* above = work.row(std::max(y - 1, 0));
    const float* middle = work.row(y);
    const float* below = work.row(std::min(y + 1, height - 1));
    float* c = column.data();
    for (int x = from(1); x < to(1); ++x) c[x] = above[x] + 2 * middle[x] + below[x];
    for (int x = x0; x < x1; ++x)
      o[x - x0] = (c[std::max(x - 1, 0)] + 2 * c[x] + c[std::min(x + 1, width - 1)]) * (1.0f / 16);
  }
}

}  // namespace

PhaseGains phaseGains(const Image& image, const CalibrationOptions& options) {
  PhaseGains gains;
  if (!isMosaic(options.colorFilter)) return gains;
  const int width = image.width(), height = image.height();
  std::vector<std::array<double, 2>> rowSums(height);
  parallelFor(0, std::size_t(height), 32, [&](std::size_t begin, std::size_t end) {
    std::vector<float> row(width);
    for (int y = int(begin); y < int(end); ++y) {
      greyRow(image, y, float(options.blackLevel), 0, width, row.data());
      double even = 0, odd = 0;
      for (int x = 0; x + 1 < width; x += 2) {
        even += row[x];
        odd += row[x + 1];
      }
      rowSums[y] = {even, odd};
    }
  });
  double phase[4] = {0, 0, 0, 0};
  for (int y = 0; y < height; ++y) {
    phase[2 * (y & 1)] += rowSums[y][0];
    phase[2 * (y & 1) + 1] += rowSums[y][1];
  }
  const double mean = 0.25 * (phase[0] + phase[1] + phase[2] + phase[3]);
  for (int p = 0; p < 4; ++p) gains.gain[p] = phase[p] > 0 && mean > 0 ? float(mean / phase[p]) : 1.0f;
  return gains;
}

Image prepareRegion(const Image& image, const CalibrationOptions& options, const PhaseGains& gains, int x0, int y0,
                    int x1, int y1, bool smoothed) {
  Image out(x1 - x0, y1 - y0, 1);
  // Bands of at least 64 rows: each band makes a few rows above and below it again.
  parallelFor(std::size_t(y0), std::size_t(y1), 128, [&](std::size_t begin, std::size_t end) {
    prepareBand(image, options, gains, x0, x1, int(begin), int(end), smoothed, out, y0);
  });
  return out;
}

Image smoothBinomial(const Image& work) {
  CalibrationOptions plain;  // one channel, no black level, no median, no binomial: the image as it is
  plain.target = CalibrationTarget::Pinhole;
  return prepareRegion(work, plain, PhaseGains{}, 0, 0, work.width(), work.height(), true);
}

Image prepareReference(const Image& image, const CalibrationOptions& options, bool smoothed) {
  const int width = image.width(), height = image.height(), channels = image.channels();
  const PhaseGains gains = phaseGains(image, options);
  Image grey(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float v = image.at(x, y, 0);
      for (int c = 1; c < channels; ++c) v += image.at(x, y, c);
      v = v / float(channels) - float(options.blackLevel);
      if (isMosaic(options.colorFilter)) v *= gains.gain[2 * (y & 1) + (x & 1)];
      grey.at(x, y, 0) = v;
    }
  Image work = options.target == CalibrationTarget::Pinhole ? std::move(grey) : median3x3Reference(grey);
  const auto clampedAt = [](const Image& im, int x, int y) {
    return im.at(std::clamp(x, 0, im.width() - 1), std::clamp(y, 0, im.height() - 1), 0);
  };
  if (isMosaic(options.colorFilter)) {
    Image alongX(width, height, 1);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        alongX.at(x, y, 0) = 0.25f * (clampedAt(work, x - 1, y) + 2 * work.at(x, y, 0) + clampedAt(work, x + 1, y));
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        work.at(x, y, 0) = 0.25f * (clampedAt(alongX, x, y - 1) + 2 * alongX.at(x, y, 0) + clampedAt(alongX, x, y + 1));
  }
  if (!smoothed) return work;
  Image alongY(width, height, 1), smooth(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      alongY.at(x, y, 0) = clampedAt(work, x, y - 1) + 2 * work.at(x, y, 0) + clampedAt(work, x, y + 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      smooth.at(x, y, 0) =
          (clampedAt(alongY, x - 1, y) + 2 * alongY.at(x, y, 0) + clampedAt(alongY, x + 1, y)) * (1.0f / 16);
  return smooth;
}

}  // namespace lfcam::calibrate_detail
