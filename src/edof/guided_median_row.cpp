// One row of the depth map's guided weighted median (edof_internal.hpp) in Highway: each window
// row of a pixel's neighbours is read as whole vectors (its colour distances, their weights from
// the table by a gather, the disparities carried along the slope), instead of one neighbour at a
// time, then the median is selected (weighted_median_select.cpp). Its reference is
// guidedWeightedMedianReference (weighted_median.cpp), whose bits it gives (no fused a * b + c:
// CMakeLists.txt). foreach_target.h compiles this file once per instruction set;
// HWY_DYNAMIC_DISPATCH picks one on the first call.
#include <algorithm>
#include <cstddef>

#include "edof/edof_internal.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "edof/guided_median_row.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace lfcam::edof {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

void GuidedMedianRow(const GuidedMedianInputs& in, int y, float* HWY_RESTRICT values, float* HWY_RESTRICT weights,
                     float* HWY_RESTRICT out) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const std::size_t lanes = hn::Lanes(d);
  const int ns = in.width, nt = in.height, radius = in.radius, channels = int(in.planes.size());
  const auto one = hn::Set(d, 1.0f), steps = hn::Set(d, float(in.steps)), half = hn::Set(d, 0.5f);
  const auto iota = hn::Iota(d, 0.0f);
  const int dyFirst = -std::min(radius, y), dyLast = std::min(radius, nt - 1 - y);
  for (int x = 0; x < ns; ++x) {
    const int dxFirst = -std::min(radius, x), dxLast = std::min(radius, ns - 1 - x);
    const std::size_t width = std::size_t(dxLast - dxFirst + 1);
    const std::size_t p = std::size_t(y) * ns + x;
    const float slopeX = in.slopeX ? in.slopeX[p] : 0.0f, slopeY = in.slopeY ? in.slopeY[p] : 0.0f;
    // The neighbours' offsets dx of a window row, a vector at a time.
    const auto firstDx = hn::Add(iota, hn::Set(d, float(dxFirst)));
    const auto slopeXs = hn::Set(d, slopeX);
    std::size_t n = 0;
    for (int dy = dyFirst; dy <= dyLast; ++dy) {
      const std::size_t row = std::size_t(long(y) + dy) * ns + std::size_t(x + dxFirst);
      const auto alongY = hn::Set(d, slopeY * float(dy));
      for (std::size_t i = 0; i < width; i += lanes) {
        auto squares = hn::Zero(d);
        for (int c = 0; c < channels; ++c) {
          const auto difference = hn::Sub(hn::LoadU(d, in.planes[c] + row + i), hn::Set(d, in.planes[c][p]));
          squares = hn::Add(squares, hn::Mul(difference, difference));
        }
        squares = hn::IfThenElse(hn::Lt(squares, one), squares, one);  // also NaN
        const auto index = hn::ConvertTo(di, hn::Add(hn::Mul(squares, steps), half));
        const auto valid = hn::FirstN(d, width - i);
        const auto weight = hn::IfThenElseZero(valid, hn::GatherIndex(d, in.table, index));
        const auto dx = hn::Add(firstDx, hn::Set(d, float(i)));
        const auto value = hn::Sub(hn::Sub(hn::LoadU(d, in.disparity + row + i), hn::Mul(slopeXs, dx)), alongY);
        // Whole vectors stored, the lanes past the window overwritten by the next (padding).
        hn::StoreU(value, d, values + n);
        hn::StoreU(weight, d, weights + n);
        n += std::min(lanes, width - i);
      }
    }
    // The total in the reference's order, one neighbour after another, so that a median at half
    // the total within a rounding is the reference's.
    float total = 0;
    for (std::size_t i = 0; i < n; ++i) total += weights[i];
    out[x] = weightedMedianSelect(values, weights, n, total);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace lfcam::edof
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam::edof {

HWY_EXPORT(GuidedMedianRow);

void guidedMedianRow(const GuidedMedianInputs& inputs, int y, float* values, float* weights, float* out) {
  HWY_DYNAMIC_DISPATCH(GuidedMedianRow)(inputs, y, values, weights, out);
}

}  // namespace lfcam::edof
#endif  // HWY_ONCE
