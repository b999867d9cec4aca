// What each view sees nearest at each of its pixels, from the centre view's disparity map: the
// test by which a focus range (focus_spread.hpp) leaves out the rays that reach a pixel through a
// surface nearer than its own. Internal to the library.
#pragma once

#include <cstddef>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"
#include "lfcam/render/focus_spread.hpp"

namespace lfcam {

class Occluders {
 public:
  // The centre's map warped into every view (a surface of disparity d at centre pixel x lies at
  // x - u d in view u), each sample splatted onto the 2 x 2 pixels around where it lands, the
  // nearest kept; pixels no sample reaches (seen only from the side) occlude nothing.
  Occluders(const LightField& lightField, const Image& disparity);

  // Whether the tap (column, row) of view (u, v) shows a surface more than kOccluderMargin nearer
  // than `ownDisparity`, the disparity of the pixel it would count for.
  bool hides(int u, int v, int row, int column, float ownDisparity) const {
    return nearest_[(std::size_t(v) * nu_ + u) * pixels_ + std::size_t(row) * ns_ + column] >
           ownDisparity + float(kOccluderMargin);
  }

 private:
  int nu_, ns_;
  std::size_t pixels_;
  std::vector<float> nearest_;
};

}  // namespace lfcam
