// Volume: an owning float32 3D image, the light-field microscope's reconstruction.
//
// Layout: voxel (x, y, z) is data()[(z * height + y) * width + x]: z-slices of row-major planes,
// the order of a TIFF stack's pages and of numpy's (z, y, x). x grows to the right and y downwards
// as in Image; slice z sits at depth firstSliceUm + z * voxelDepthUm in the specimen (z grows
// toward the objective, napari-LF's convention).
//
// Move-only, as Image.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace lfcam {

class Volume {
 public:
  Volume() = default;
  // Zero-filled. Dimensions must be non-negative.
  Volume(int width, int height, int depth)
      : width_(width), height_(height), depth_(depth), data_(std::size_t(width) * height * depth) {}

  Volume(Volume&&) noexcept = default;
  Volume& operator=(Volume&&) noexcept = default;
  Volume(const Volume&) = delete;
  Volume& operator=(const Volume&) = delete;
  Volume copy() const {
    Volume out(width_, height_, depth_);
    out.data_ = data_;
    out.voxelWidthUm = voxelWidthUm, out.voxelHeightUm = voxelHeightUm, out.voxelDepthUm = voxelDepthUm;
    out.firstSliceUm = firstSliceUm;
    return out;
  }

  int width() const { return width_; }
  int height() const { return height_; }
  int depth() const { return depth_; }
  bool empty() const { return data_.empty(); }
  std::size_t sliceSize() const { return std::size_t(width_) * std::size_t(height_); }

  float* slice(int z) { return data_.data() + std::size_t(z) * sliceSize(); }
  const float* slice(int z) const { return data_.data() + std::size_t(z) * sliceSize(); }
  float& at(int x, int y, int z) { return slice(z)[std::size_t(y) * width_ + x]; }
  float at(int x, int y, int z) const { return slice(z)[std::size_t(y) * width_ + x]; }

  std::span<float> voxels() { return data_; }
  std::span<const float> voxels() const { return data_; }

  // Micrometres in the specimen: the voxel along x and y (a hexagonal microlens array's rows make
  // them differ), the slice spacing, and the depth of slice 0 from the native object plane.
  double voxelWidthUm = 1, voxelHeightUm = 1, voxelDepthUm = 1, firstSliceUm = 0;

 private:
  int width_ = 0, height_ = 0, depth_ = 0;
  std::vector<float> data_;
};

}  // namespace lfcam
