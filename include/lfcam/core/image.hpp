// Image: an owning float32 image with planar channels.
//
// Layout: channel c is a row-major plane of width*height floats; pixel (x, y) of channel c is
// data()[(c * height + y) * width + x]. x grows to the right, y grows downwards, and pixel
// (x, y) covers the square [x, x+1) x [y, y+1), so its centre is at (x + 0.5, y + 0.5).
// Values are linear light; integer files are scaled to [0, 1] (see image_io.hpp).
//
// Move-only: a copy of a large buffer must be asked for with copy(), never made by accident.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace lfcam {

class Image {
 public:
  Image() = default;
  // Zero-filled. Dimensions must be non-negative.
  Image(int width, int height, int channels);

  Image(Image&&) noexcept = default;
  Image& operator=(Image&&) noexcept = default;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;
  Image copy() const;

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  bool empty() const { return data_.empty(); }
  std::size_t planeSize() const { return std::size_t(width_) * std::size_t(height_); }

  float* plane(int c) { return data_.data() + std::size_t(c) * planeSize(); }
  const float* plane(int c) const { return data_.data() + std::size_t(c) * planeSize(); }
  float* row(int y, int c) { return plane(c) + std::size_t(y) * width_; }
  const float* row(int y, int c) const { return plane(c) + std::size_t(y) * width_; }
  float& at(int x, int y, int c) { return row(y, c)[x]; }
  float at(int x, int y, int c) const { return row(y, c)[x]; }

  std::span<float> pixels() { return data_; }
  std::span<const float> pixels() const { return data_; }

 private:
  int width_ = 0, height_ = 0, channels_ = 0;
  std::vector<float> data_;
};

}  // namespace lfcam
