#include "lfcam/core/light_field.hpp"

#include <algorithm>
#include <cassert>

namespace lfcam {

double Optics::slopeFromAlpha(double alpha) const { return lensStepMm / spatialStepMm * (1.0 - 1.0 / alpha); }

double Optics::alphaFromSlope(double slope) const { return 1.0 / (1.0 - slope * spatialStepMm / lensStepMm); }

LightField::LightField(const LightFieldShape& shape, Pages pages)
    : shape_(shape), data_(shape.samples(), HugePageAllocator<float>(pages)) {
  assert(shape.nu >= 0 && shape.nv >= 0 && shape.ns >= 0 && shape.nt >= 0 && shape.channels >= 0);
}

LightField LightField::copy() const {
  LightField result;
  result.shape_ = shape_;
  result.data_ = data_;
  result.weight_ = weight_;
  result.metadata = metadata;
  return result;
}

void LightField::enableWeight(float value) {
  // A fresh buffer, on the samples' kind of pages, is already zero (huge_page_allocator.hpp).
  decltype(weight_) fresh(shape_.views() * shape_.viewPixels(), data_.get_allocator());
  if (value != 0.0f) std::fill(fresh.begin(), fresh.end(), value);
  weight_.swap(fresh);
}

Image LightField::subApertureImage(int u, int v) const {
  Image image(shape_.ns, shape_.nt, shape_.channels);
  for (int c = 0; c < shape_.channels; ++c) std::copy_n(plane(u, v, c), shape_.viewPixels(), image.plane(c));
  return image;
}

void LightField::setSubApertureImage(int u, int v, const Image& image) {
  assert(image.width() == shape_.ns && image.height() == shape_.nt && image.channels() == shape_.channels);
  for (int c = 0; c < shape_.channels; ++c) std::copy_n(image.plane(c), shape_.viewPixels(), plane(u, v, c));
}

}  // namespace lfcam
