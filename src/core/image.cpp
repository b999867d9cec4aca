#include "lfcam/core/image.hpp"

#include <cassert>

namespace lfcam {

Image::Image(int width, int height, int channels)
    : width_(width),
      height_(height),
      channels_(channels),
      data_(std::size_t(width) * std::size_t(height) * std::size_t(channels), 0.0f) {
  assert(width >= 0 && height >= 0 && channels >= 0);
}

Image Image::copy() const {
  Image result(width_, height_, channels_);
  result.data_ = data_;
  return result;
}

}  // namespace lfcam
