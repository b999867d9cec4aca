// One row of focused depth's raw cost (focused_depth.cpp) at one virtual depth v: at each pixel Q
// of the photograph's frame, the weighted variance of the samples of the luminance that the
// micro-images whose disc holds S give (weights 1 - rho^2, as MicroImageViews visits them), 0
// where fewer than two see Q, and whether two do (1 or 0).
//
// The fast kernel goes lens by lens, each over the span of the row its disc covers (the lenses
// listed per row beforehand, LensesByRow), a vector of pixels at a time in float through Highway
// with run-time dispatch; a point's lenses add in the grid's (j, i) order, as in the reference.
// The scalar reference goes pixel by pixel through MicroImageViews, in double.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "focused/micro_image_views.hpp"
#include "lfcam/core/image.hpp"
#include "lfcam/focused/photo_frame.hpp"

namespace lfcam::focused_detail {

// The lenses whose disc of radius `discRadius` (image pixels) around their centre meets each of
// the frame's rows [firstRow, endRow) (within half a pixel), in the grid's (j, i) order. `views`
// outlives this.
class LensesByRow {
 public:
  LensesByRow(const MicroImageViews& views, const FocusedPhotoFrame& frame, double discRadius, int firstRow,
              int endRow);

  double discRadius() const { return discRadius_; }
  const std::array<double, 2>& centre(std::uint32_t lens) const { return (*centres_)[lens]; }
  std::span<const std::uint32_t> row(int py) const {
    const std::size_t k = std::size_t(py - firstRow_);
    return {lenses_.data() + starts_[k], lenses_.data() + starts_[k + 1]};
  }

 private:
  double discRadius_;
  int firstRow_;
  const std::vector<std::array<double, 2>>* centres_;
  std::vector<std::size_t> starts_;  // row py's lenses: [starts_[py - firstRow], starts_[py - firstRow + 1])
  std::vector<std::uint32_t> lenses_;
};

// The sums one row gathers (the span's width plus a vector's padding each).
struct DisagreementSums {
  std::vector<float> weight, value, square, seen;
};

// Pixels [begin, end) of row py of the raw cost and of the two-or-more mask, into raw[0, end -
// begin) and seen[...], at v with the lenses' discs of radius v * (the micro-images' usable radius)
// = lenses.discRadius(). `sign`: the micro-images' orientation (FocusedCalibration::orientationSign).
void disagreementRow(const Image& grey, const LensesByRow& lenses, const FocusedPhotoFrame& frame, double v,
                     double sign, int py, int begin, int end, DisagreementSums& sums, float* raw, float* seen);

void disagreementRowReference(const Image& grey, const MicroImageViews& views, const FocusedPhotoFrame& frame, double v,
                              int py, int begin, int end, float* raw, float* seen);

}  // namespace lfcam::focused_detail
