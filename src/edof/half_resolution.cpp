// Light fields, images and maps at half the resolution and back (depth_stages.hpp): where the first
// maps of the view offsets and the coarse cost of noisy views are made.
#include "core/bilinear.hpp"
#include "core/parallel.hpp"
#include "edof/depth_stages.hpp"

namespace lfcam::edof {

namespace {

// A plane of width x height at half the resolution (means of 2x2 pixels; an odd last row or
// column left out): where the first maps of the view offsets are made.
void halvePlane(const float* in, int width, int height, float* out) {
  for (int y = 0; y < height / 2; ++y)
    for (int x = 0; x < width / 2; ++x) {
      const float* p = in + std::size_t(2 * y) * width + 2 * x;
      out[std::size_t(y) * (width / 2) + x] = 0.25f * (p[0] + p[1] + p[width] + p[width + 1]);
    }
}

}  // namespace

double sampleHalfResolution(const float* half, int halfWidth, int halfHeight, int x, int y) {
  return bilinearSample(half, halfWidth, halfHeight, 0.5 * x - 0.25, 0.5 * y - 0.25);
}

LightField halfResolution(const LightField& in) {
  LightFieldShape shape = in.shape();
  shape.ns /= 2, shape.nt /= 2;
  LightField out(shape);
  out.metadata = in.metadata;
  parallelFor(0, shape.views() * std::size_t(shape.channels), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t index = begin; index < end; ++index) {
      const int c = int(index % std::size_t(shape.channels));
      const std::size_t view = index / std::size_t(shape.channels);
      const int u = int(view % in.nu()), v = int(view / in.nu());
      halvePlane(in.plane(u, v, c), in.ns(), in.nt(), out.plane(u, v, c));
    }
  });
  return out;
}

Image halfResolution(const Image& in) {
  Image out(in.width() / 2, in.height() / 2, in.channels());
  for (int c = 0; c < in.channels(); ++c) halvePlane(in.plane(c), in.width(), in.height(), out.plane(c));
  return out;
}

Image fullResolution(const Image& half, int width, int height) {
  Image out(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      out.at(x, y, 0) = 2 * sampleHalfResolution(half.plane(0), half.width(), half.height(), x, y);
  return out;
}

}  // namespace lfcam::edof
