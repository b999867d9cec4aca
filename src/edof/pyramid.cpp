// Laplacian-pyramid blending (Burt and Adelson 1983), edof_internal.hpp. The 5-tap binomial
// kernel [1 4 6 4 1] / 16, borders clamped. Reconstruction is exact whatever the borders do,
// because each band is stored as the difference with the same expand() that collapses it.
#include <algorithm>

#include "core/parallel.hpp"
#include "edof/edof_internal.hpp"

namespace lfcam::edof {

namespace {

struct Plane {
  int width = 0, height = 0;
  std::vector<float> data;
};

// Blur with [1 4 6 4 1] / 16 and keep every other sample: (w + 1) / 2 x (h + 1) / 2.
// Schedule: vertical pass first over whole rows (five row pointers, clamped once per row, a
// straight loop that vectorises), then the horizontal pass with clamping only at the ends.
Plane reduce(const Plane& in) {
  const int w = (in.width + 1) / 2, h = (in.height + 1) / 2;
  Plane out{w, h, std::vector<float>(std::size_t(w) * h)};
  std::vector<float> column(in.width);
  for (int y = 0; y < h; ++y) {
    const float* r[5];
    for (int k = 0; k < 5; ++k)
      r[k] = in.data.data() + std::size_t(std::clamp(2 * y - 2 + k, 0, in.height - 1)) * in.width;
    for (int x = 0; x < in.width; ++x)
      column[x] = (r[0][x] + 4 * r[1][x] + 6 * r[2][x] + 4 * r[3][x] + r[4][x]) * (1.0f / 16);
    float* target = out.data.data() + std::size_t(y) * w;
    auto at = [&](int x) { return column[std::clamp(x, 0, in.width - 1)]; };
    for (int x = 0; x < w; ++x) {
      const int c = 2 * x;
      if (c >= 2 && c + 2 < in.width)
        target[x] =
            (column[c - 2] + 4 * column[c - 1] + 6 * column[c] + 4 * column[c + 1] + column[c + 2]) * (1.0f / 16);
      else
        target[x] = (at(c - 2) + 4 * at(c - 1) + 6 * at(c) + 4 * at(c + 1) + at(c + 2)) * (1.0f / 16);
    }
  }
  return out;
}

// Upsample to width x height: zeros between samples, then the kernel times 2 per axis. Even
// outputs take (1 6 1) / 8 of the samples around them, odd outputs (1 1) / 2.
Plane expand(const Plane& in, int width, int height) {
  Plane out{width, height, std::vector<float>(std::size_t(width) * height)};
  std::vector<float> row(in.width);
  const int last = in.height - 1;
  for (int y = 0; y < height; ++y) {
    // Vertical: the row of `in` at output row y.
    auto inRow = [&](int i) { return in.data.data() + std::size_t(std::clamp(i, 0, last)) * in.width; };
    if (y % 2 == 0) {
      const float *a = inRow(y / 2 - 1), *b = inRow(y / 2), *c = inRow(y / 2 + 1);
      for (int x = 0; x < in.width; ++x) row[x] = (a[x] + 6 * b[x] + c[x]) * (1.0f / 8);
    } else {
      const float *a = inRow((y - 1) / 2), *b = inRow((y + 1) / 2);
      for (int x = 0; x < in.width; ++x) row[x] = (a[x] + b[x]) * 0.5f;
    }
    // Horizontal.
    auto at = [&](int i) { return row[std::clamp(i, 0, in.width - 1)]; };
    float* target = out.data.data() + std::size_t(y) * width;
    for (int x = 0; x < width; ++x) {
      const int i = x / 2;
      if (x % 2 == 0)
        target[x] = (i >= 1 && i + 1 < in.width) ? (row[i - 1] + 6 * row[i] + row[i + 1]) * (1.0f / 8)
                                                 : (at(i - 1) + 6 * at(i) + at(i + 1)) * (1.0f / 8);
      else
        target[x] = (i + 1 < in.width) ? (row[i] + row[i + 1]) * 0.5f : (at(i) + at(i + 1)) * 0.5f;
    }
  }
  return out;
}

}  // namespace

PyramidBlender::PyramidBlender(int width, int height, int channels, int levels) : channels_(channels) {
  for (int l = 0; l < std::max(levels, 1); ++l) {
    accumulator_.push_back({width, height, std::vector<float>(std::size_t(width) * height * channels, 0.0f)});
    if (width <= 1 && height <= 1) break;
    width = (width + 1) / 2, height = (height + 1) / 2;
  }
}

void PyramidBlender::add(const Image& image, const float* weight) {
  const int levels = int(accumulator_.size());
  // Gaussian pyramid of the weight.
  std::vector<Plane> mask(levels);
  mask[0] = Plane{image.width(), image.height(), std::vector<float>(weight, weight + image.planeSize())};
  for (int l = 1; l < levels; ++l) mask[l] = reduce(mask[l - 1]);
  // Laplacian pyramid of each channel, weighted into the accumulator. Channels in parallel.
  parallelFor(0, std::size_t(channels_), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      Plane gaussian{image.width(), image.height(),
                     std::vector<float>(image.plane(int(c)), image.plane(int(c)) + image.planeSize())};
      for (int l = 0; l < levels; ++l) {
        Level& target = accumulator_[l];
        const std::size_t n = std::size_t(target.width) * target.height;
        float* out = target.data.data() + c * n;
        if (l + 1 == levels) {
          for (std::size_t i = 0; i < n; ++i) out[i] += mask[l].data[i] * gaussian.data[i];
          break;
        }
        Plane smaller = reduce(gaussian);
        const Plane back = expand(smaller, gaussian.width, gaussian.height);
        for (std::size_t i = 0; i < n; ++i) out[i] += mask[l].data[i] * (gaussian.data[i] - back.data[i]);
        gaussian = std::move(smaller);
      }
    }
  });
}

Image PyramidBlender::result() const {
  const int levels = int(accumulator_.size());
  Image out(accumulator_[0].width, accumulator_[0].height, channels_);
  for (int c = 0; c < channels_; ++c) {
    const Level& top = accumulator_[levels - 1];
    const std::size_t topSize = std::size_t(top.width) * top.height;
    Plane image{top.width, top.height,
                std::vector<float>(top.data.begin() + c * topSize, top.data.begin() + (c + 1) * topSize)};
    for (int l = levels - 2; l >= 0; --l) {
      const Level& level = accumulator_[l];
      const std::size_t n = std::size_t(level.width) * level.height;
      image = expand(image, level.width, level.height);
      for (std::size_t i = 0; i < n; ++i) image.data[i] += level.data[c * n + i];
    }
    std::copy(image.data.begin(), image.data.end(), out.plane(c));
  }
  return out;
}

}  // namespace lfcam::edof
