// Luminance, box filter, guided filter and central differences (edof_internal.hpp).
#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"
#include "core/separable_filter.hpp"
#include "edof/edof_internal.hpp"

namespace lfcam::edof {

namespace {

void luminanceOfPlanes(const float* const* planes, int channels, std::size_t count, float* out) {
  if (channels == 3) {
    for (std::size_t i = 0; i < count; ++i)
      out[i] = 0.2126f * planes[0][i] + 0.7152f * planes[1][i] + 0.0722f * planes[2][i];
    return;
  }
  const float scale = 1.0f / float(std::max(channels, 1));
  std::fill(out, out + count, 0.0f);
  for (int c = 0; c < channels; ++c)
    for (std::size_t i = 0; i < count; ++i) out[i] += scale * planes[c][i];
}

}  // namespace

Image luminance(const Image& image) {
  Image out(image.width(), image.height(), 1);
  std::vector<const float*> planes;
  for (int c = 0; c < image.channels(); ++c) planes.push_back(image.plane(c));
  luminanceOfPlanes(planes.data(), image.channels(), image.planeSize(), out.plane(0));
  return out;
}

LightField luminanceLightField(const LightField& lightField) {
  LightFieldShape shape = lightField.shape();
  shape.channels = 1;
  LightField out(shape);
  out.metadata = lightField.metadata;
  parallelFor(0, shape.views(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t view = begin; view < end; ++view) {
      const int u = int(view % shape.nu), v = int(view / shape.nu);
      std::vector<const float*> planes;
      for (int c = 0; c < lightField.channels(); ++c) planes.push_back(lightField.plane(u, v, c));
      luminanceOfPlanes(planes.data(), lightField.channels(), shape.viewPixels(), out.plane(u, v, 0));
    }
  });
  if (lightField.hasWeight()) {
    out.enableWeight();
    std::copy(lightField.weights().begin(), lightField.weights().end(), out.weights().begin());
  }
  return out;
}

namespace {

// The guided filter's box filters for radii up to kSmallRadius: float sums of the window's rows,
// then of its columns, a row at a time; a few vectorised adds per pixel (and no drift, unlike
// running sums), where boxFilter's double prefix sums are a serial chain with a division per
// pixel.
constexpr int kSmallRadius = 8;

// Row y of the mean over rows [y - r, y + r] (clipped) of `in`, times `weight` per pixel when it
// is given (the guided filter's I p without a plane of its own).
LFCAM_CLONES void columnMeanRow(const float* __restrict in, const float* __restrict weight, int width, int height,
                                int y, int radius, float* __restrict target) {
  const int y0 = std::max(0, y - radius), y1 = std::min(height, y + radius + 1);
  std::fill(target, target + width, 0.0f);
  for (int yy = y0; yy < y1; ++yy) {
    const float* row = in + std::size_t(yy) * width;
    if (weight) {
      const float* w = weight + std::size_t(yy) * width;
      for (int x = 0; x < width; ++x) target[x] += w[x] * row[x];
    } else {
      for (int x = 0; x < width; ++x) target[x] += row[x];
    }
  }
  const float inverse = 1.0f / float(y1 - y0);
  for (int x = 0; x < width; ++x) target[x] *= inverse;
}

// The mean of `count` rows given in order, as columnMeanRow sums them (the same bits).
LFCAM_CLONES void columnMeanOfRows(const float* const* rows, int count, int width, float* __restrict target) {
  std::fill(target, target + width, 0.0f);
  for (int k = 0; k < count; ++k) {
    const float* __restrict row = rows[k];
    for (int x = 0; x < width; ++x) target[x] += row[x];
  }
  const float inverse = 1.0f / float(count);
  for (int x = 0; x < width; ++x) target[x] *= inverse;
}

// The mean over [x - r, x + r] (clipped) of one row: the interior as 2 r + 1 vectorised passes.
LFCAM_CLONES void rowMean(const float* __restrict row, int width, int radius, float* __restrict target) {
  auto clipped = [&](int x) {
    const int x0 = std::max(0, x - radius), x1 = std::min(width, x + radius + 1);
    float sum = 0;
    for (int xx = x0; xx < x1; ++xx) sum += row[xx];
    target[x] = sum / float(x1 - x0);
  };
  const int interiorEnd = std::max(radius, width - radius);
  for (int x = 0; x < std::min(radius, width); ++x) clipped(x);
  for (int x = interiorEnd; x < width; ++x) clipped(x);
  if (interiorEnd <= radius) return;
  const float inverse = 1.0f / float(2 * radius + 1);
  for (int x = radius; x < interiorEnd; ++x) target[x] = row[x - radius];
  for (int k = 1 - radius; k <= radius; ++k)
    for (int x = radius; x < interiorEnd; ++x) target[x] += row[x + k];
  for (int x = radius; x < interiorEnd; ++x) target[x] *= inverse;
}

}  // namespace

GuidedFilter::GuidedFilter(const float* guide, int width, int height, int radius, double epsilon)
    : width_(width), height_(height), radius_(radius) {
  const std::size_t n = std::size_t(width) * height;
  guide_.assign(guide, guide + n);
  meanGuide_.resize(n);
  inverseVariance_.resize(n);
  boxFilter(guide, meanGuide_.data(), width, height, radius);
  std::vector<float> squares(n), meanSquares(n);
  for (std::size_t i = 0; i < n; ++i) squares[i] = guide[i] * guide[i];
  boxFilter(squares.data(), meanSquares.data(), width, height, radius);
  for (std::size_t i = 0; i < n; ++i) {
    const double variance = std::max(0.0, double(meanSquares[i]) - double(meanGuide_[i]) * meanGuide_[i]);
    inverseVariance_[i] = float(1.0 / (variance + epsilon));
  }
}

void GuidedFilter::apply(const float* in, float* out) const {
  Scratch scratch;
  apply(in, out, scratch);
}

// q = mean(a) I + mean(b), a = cov(I, p) / (var(I) + eps), b = mean(p) - a mean(I). The guide's
// statistics come from the constructor. Small windows: one sweep of rows, a and b kept for the
// 2 r + 1 rows the window needs (a ring of rows in cache, where whole planes of a and b cost two
// planes written and read again per input), each row's sums in row buffers. In place too: input
// row y is last read for a and b's row y + r, made before output row y is written.
void GuidedFilter::apply(const float* in, float* out, Scratch& scratch) const {
  const int w = width_, h = height_, r = radius_;
  const std::size_t n = std::size_t(w) * h;
  scratch.rows.resize(4 * std::size_t(w));
  float* column0 = scratch.rows.data();
  float* column1 = column0 + w;
  float* mean0 = column1 + w;
  float* mean1 = mean0 + w;
  if (r > kSmallRadius) {  // wide windows: whole-plane running sums
    scratch.a.resize(n);
    scratch.b.resize(n);
    float* a = scratch.a.data();
    float* b = scratch.b.data();
    std::vector<float>&product = scratch.product, &meanIn = scratch.meanIn, &meanProduct = scratch.meanProduct;
    product.resize(n), meanIn.resize(n), meanProduct.resize(n);
    for (std::size_t i = 0; i < n; ++i) product[i] = guide_[i] * in[i];
    boxFilter(in, meanIn.data(), w, h, r);
    boxFilter(product.data(), meanProduct.data(), w, h, r);
    for (std::size_t i = 0; i < n; ++i) {
      a[i] = (meanProduct[i] - meanGuide_[i] * meanIn[i]) * inverseVariance_[i];
      b[i] = meanIn[i] - a[i] * meanGuide_[i];
    }
    boxFilter(a, meanIn.data(), w, h, r);
    boxFilter(b, out, w, h, r);
    for (std::size_t i = 0; i < n; ++i) out[i] += meanIn[i] * guide_[i];
    return;
  }
  const int ringRows = 2 * r + 1;
  scratch.a.resize(std::size_t(ringRows) * w);
  scratch.b.resize(std::size_t(ringRows) * w);
  const auto ringRow = [&](std::vector<float>& ring, int y) { return ring.data() + std::size_t(y % ringRows) * w; };
  std::vector<const float*>& aRows = scratch.ringA;
  std::vector<const float*>& bRows = scratch.ringB;
  int made = 0;  // rows of a and b made so far
  for (int y = 0; y < h; ++y) {
    for (; made < std::min(h, y + r + 1); ++made) {
      columnMeanRow(in, nullptr, w, h, made, r, column0);
      columnMeanRow(in, guide_.data(), w, h, made, r, column1);
      rowMean(column0, w, r, mean0);
      rowMean(column1, w, r, mean1);
      const std::size_t row = std::size_t(made) * w;
      float* a = ringRow(scratch.a, made);
      float* b = ringRow(scratch.b, made);
      for (int x = 0; x < w; ++x) {
        const float slope = (mean1[x] - meanGuide_[row + x] * mean0[x]) * inverseVariance_[row + x];
        a[x] = slope;
        b[x] = mean0[x] - slope * meanGuide_[row + x];
      }
    }
    const int y0 = std::max(0, y - r), y1 = std::min(h, y + r + 1);
    aRows.clear(), bRows.clear();
    for (int yy = y0; yy < y1; ++yy) aRows.push_back(ringRow(scratch.a, yy)), bRows.push_back(ringRow(scratch.b, yy));
    columnMeanOfRows(aRows.data(), int(aRows.size()), w, column0);
    columnMeanOfRows(bRows.data(), int(bRows.size()), w, column1);
    rowMean(column0, w, r, mean0);
    rowMean(column1, w, r, mean1);
    const std::size_t row = std::size_t(y) * w;
    for (int x = 0; x < w; ++x) out[row + x] = mean0[x] * guide_[row + x] + mean1[x];
  }
}

std::vector<float> gaussianTaps(double sigma) {
  const int radius = std::max(1, int(std::ceil(3 * sigma)));
  std::vector<float> taps(2 * radius + 1);
  double total = 0;
  for (int k = -radius; k <= radius; ++k) total += taps[k + radius] = float(std::exp(-0.5 * k * k / (sigma * sigma)));
  for (float& tap : taps) tap = float(tap / total);
  return taps;
}

void gaussianBlur(float* plane, int width, int height, double sigma) {
  if (!(sigma > 0)) return;
  separableFilter(plane, plane, width, height, gaussianTaps(sigma));
}

void squaredLaplacian(const Image& image, float* out) {
  const int w = image.width(), h = image.height();
  const float* p = image.plane(0);
  parallelFor(0, std::size_t(h), 16, [&](std::size_t begin, std::size_t end) {
    for (int y = int(begin); y < int(end); ++y) {
      const float* row = p + std::size_t(y) * w;
      const float* above = p + std::size_t(std::max(y - 1, 0)) * w;
      const float* below = p + std::size_t(std::min(y + 1, h - 1)) * w;
      float* target = out + std::size_t(y) * w;
      const auto at = [&](int x, int xa, int xb) {
        const float lap = row[xa] + row[xb] + above[x] + below[x] - 4 * row[x];
        target[x] = lap * lap;
      };
      // The interior without the border's clamps, so that it vectorises.
      for (int x = 1; x + 1 < w; ++x) at(x, x - 1, x + 1);
      at(0, 0, std::min(1, w - 1));
      if (w > 1) at(w - 1, w - 2, w - 1);
    }
  });
}

void centralDifferences(const float* in, int ns, int nt, float scale, float* dx, float* dy) {
  for (int y = 0; y < nt; ++y) {
    const float *row = in + std::size_t(y) * ns, *up = in + std::size_t(std::max(y - 1, 0)) * ns,
                *down = in + std::size_t(std::min(y + 1, nt - 1)) * ns;
    for (int x = 0; x < ns; ++x) {
      dx[std::size_t(y) * ns + x] = 0.5f * scale * (row[std::min(x + 1, ns - 1)] - row[std::max(x - 1, 0)]);
      dy[std::size_t(y) * ns + x] = 0.5f * scale * (down[x] - up[x]);
    }
  }
}

}  // namespace lfcam::edof
