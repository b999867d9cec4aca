// Dicing: every microlens image sampled into the views of L(u, v, s, t).
//
// SubPixel: view (u, v) of microlens (i, j) is the raw's point centre(i, j) + (u - (n-1)/2,
// v - (n-1)/2), interpolated with a Catmull-Rom cubic. All views of one microlens share the same
// sub-pixel phase (they are whole pixels apart), so the fast kernel filters the microlens's patch
// separably with one set of 4 weights per axis: (n + 3) n 4 + n n 4 multiply-adds per microlens and
// channel instead of 16 n n.
// IntegralPitch (the paper's section 5.2): the raw rotated and scaled to round(pitch) pixels per
// microlens with bilinear interpolation, then diced; sampled here directly at the points that
// resampling and dicing would read, which gives the same values without the resampled image.
// Bricks: as SubPixel, the views a step of the lattice's axes apart that tiles each brick.
#include <algorithm>
#include <cmath>

#include "core/cubic.hpp"
#include "core/parallel.hpp"
#include "decode/decode_internal.hpp"

namespace lfcam::decode_detail {

namespace {

inline int clampIndex(int i, int n) { return std::clamp(i, 0, n - 1); }

// Cubic (or bilinear) interpolation of one plane at array coordinates (x, y) (pixel centres at
// integers), borders clamped.
float interpolate(const float* plane, int w, int h, double x, double y, bool cubic) {
  if (cubic) return cubicSample(plane, w, h, x, y, kCatmullRom);
  const int bx = int(std::floor(x)), by = int(std::floor(y));
  const double fx = x - bx, fy = y - by;
  auto at = [&](int xx, int yy) { return plane[std::size_t(clampIndex(yy, h)) * w + clampIndex(xx, w)]; };
  return float((1 - fy) * ((1 - fx) * at(bx, by) + fx * at(bx + 1, by)) +
               fy * ((1 - fx) * at(bx, by + 1) + fx * at(bx + 1, by + 1)));
}

inline float cleanWeight(float w) { return w < 0.02f ? 0.0f : std::min(w, 1.0f); }

// One microlens, one sample at a time (the reference, and the path for microlenses at the border).
void sampleMicrolensPlain(const Image& planes, const Image& weight, const LensletGrid& grid, const ViewLayout& layout,
                          LightField& lf, int i, int j) {
  const int n = layout.views, w = planes.width(), h = planes.height();
  const int s = i, t = j - layout.firstRow;
  const auto centre = grid.centre(i, j);
  const bool cubic = layout.sampling != Sampling::IntegralPitch;
  const double cs = std::cos(grid.rotationRad), sn = std::sin(grid.rotationRad);
  for (int v = 0; v < n; ++v)
    for (int u = 0; u < n; ++u) {
      double ox = u - 0.5 * (n - 1), oy = v - 0.5 * (n - 1);
      if (layout.sampling != Sampling::SubPixel) {  // the lattice's axes, a step apart
        const double rx = ox * layout.step[0], ry = oy * layout.step[1];
        ox = cs * rx - sn * ry, oy = sn * rx + cs * ry;
      }
      const double x = centre[0] + ox, y = centre[1] + oy;
      const std::size_t k = std::size_t(t) * lf.ns() + s;
      for (int c = 0; c < planes.channels(); ++c)
        lf.plane(u, v, c)[k] = interpolate(planes.plane(c), w, h, x - 0.5, y - 0.5, cubic);
      float wt = x >= 0 && y >= 0 && x < w && y < h ? 1.0f : 0.0f;
      if (wt > 0 && !weight.empty()) wt = cleanWeight(interpolate(weight.plane(0), w, h, x - 0.5, y - 0.5, cubic));
      lf.weightPlane(u, v)[k] = wt;
    }
}

// One microlens, separable: the fast kernel of SubPixel sampling. Both passes run over
// contiguous, forward arrays (view u lies u pixels right of view 0) so that the compiler
// vectorises them. Writes out[p * n * n + v * n + u] for plane p (the channels, then the weight);
// `rows` holds (n + 3) * n floats. Returns false when the patch reaches beyond
// the image (caller falls back).
bool sampleMicrolensSeparable(const Image& planes, const Image& weight, const LensletGrid& grid, int n, int i, int j,
                              float* rows, float* out) {
  const int w = planes.width(), h = planes.height();
  const auto centre = grid.centre(i, j);
  // Array coordinate of view 0 (the leftmost/highest point); view u is u pixels right of it.
  const double x0 = centre[0] - 0.5 * (n - 1) - 0.5, y0 = centre[1] - 0.5 * (n - 1) - 0.5;
  const int bx = int(std::floor(x0)), by = int(std::floor(y0));
  const int left = bx - 1, top = by - 1;  // first tap column / row (of view 0)
  if (left < 0 || top < 0 || bx + n + 1 >= w || by + n + 1 >= h) return false;
  float wx[4], wy[4];
  keysCubicWeights(x0 - bx, kCatmullRom, wx);
  keysCubicWeights(y0 - by, kCatmullRom, wy);
  auto filter = [&](const float* plane, float* o) {
    // Horizontal pass over the n + 3 rows the vertical taps need: rows[r * n + u].
    for (int r = 0; r < n + 3; ++r) {
      const float* src = plane + std::size_t(top + r) * w + left;
      float* dst = rows + std::size_t(r) * n;
      for (int u = 0; u < n; ++u)
        dst[u] = wx[0] * src[u] + wx[1] * src[u + 1] + wx[2] * src[u + 2] + wx[3] * src[u + 3];
    }
    // Vertical pass: view v reads rows v .. v+3.
    for (int v = 0; v < n; ++v, o += n) {
      const float* r0 = rows + std::size_t(v) * n;
      for (int u = 0; u < n; ++u)
        o[u] = wy[0] * r0[u] + wy[1] * r0[u + n] + wy[2] * r0[u + 2 * n] + wy[3] * r0[u + 3 * n];
    }
  };
  const std::size_t views = std::size_t(n) * n;
  for (int c = 0; c < planes.channels(); ++c) filter(planes.plane(c), out + std::size_t(c) * views);
  float* o = out + std::size_t(planes.channels()) * views;
  if (weight.empty()) {
    std::fill(o, o + views, 1.0f);
  } else {
    filter(weight.plane(0), o);
    for (std::size_t m = 0; m < views; ++m) o[m] = cleanWeight(o[m]);
  }
  return true;
}

}  // namespace

void sampleLenslets(const Image& planes, const Image& weight, const LensletGrid& grid, const ViewLayout& layout,
                    LightField& lf, bool reference) {
  const int n = layout.views, channels = planes.channels();
  const bool separable = !reference && layout.sampling == Sampling::SubPixel;
  // The fast kernel fills a batch of neighbouring microlenses of one row into a buffer, then writes
  // each view plane's run of them at once: one pass over each plane's cache line per batch
  // instead of one per microlens (the views are (channels + 1) n^2 planes apart in memory).
  constexpr int kBatch = 16;
  const std::size_t perLens = std::size_t(channels + 1) * n * n;
  parallelFor(std::size_t(layout.firstRow), std::size_t(grid.rows), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> rows(std::size_t(n + 3) * n), buffer(perLens * kBatch);
    for (int j = int(begin); j < int(end); ++j) {
      const int t = j - layout.firstRow;
      for (int i0 = 0; i0 < grid.columns; i0 += kBatch) {
        const int count = std::min(kBatch, grid.columns - i0);
        bool done[kBatch] = {};
        for (int b = 0; b < count; ++b) {
          done[b] = separable && sampleMicrolensSeparable(planes, weight, grid, n, i0 + b, j, rows.data(),
                                                          buffer.data() + std::size_t(b) * perLens);
          if (!done[b]) sampleMicrolensPlain(planes, weight, grid, layout, lf, i0 + b, j);
        }
        if (!separable) continue;
        // Microlens i0 + b is sample s = i0 + b.
        const std::size_t k0 = std::size_t(t) * lf.ns() + std::size_t(i0);
        for (int p = 0; p <= channels; ++p)
          for (int v = 0; v < n; ++v)
            for (int u = 0; u < n; ++u) {
              float* dst = (p < channels ? lf.plane(u, v, p) : lf.weightPlane(u, v)) + k0;
              const float* src = buffer.data() + std::size_t(p) * n * n + std::size_t(v) * n + u;
              for (int b = 0; b < count; ++b)
                if (done[b]) dst[b] = src[std::size_t(b) * perLens];
            }
      }
    }
  });
}

}  // namespace lfcam::decode_detail
