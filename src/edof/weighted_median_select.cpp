// The weighted median's selection (edof_internal.hpp) in Highway: each pass tallies the weight
// below and at a pivot over whole vectors of the window, in lanes of doubles (the guide's table
// gives weights so far apart that their sums in float are not exact), and compacts the side that
// holds the median with CompressBlendedStore, without a branch per entry (the comparisons of a
// median's window are as good as random). Its reference is weightedMedianSorted
// (weighted_median.cpp). foreach_target.h compiles this file once per instruction set;
// HWY_DYNAMIC_DISPATCH picks one on the first call.
#include <algorithm>
#include <cstddef>

#include "edof/edof_internal.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "edof/weighted_median_select.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace lfcam::edof {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

using DD = hn::ScalableTag<double>;
using DF = hn::Rebind<float, DD>;
using VD = hn::Vec<DD>;
using VF = hn::Vec<DF>;
using MF = hn::Mask<DF>;

// Keeps, in order, the entries of [0, n) whose value `keep` accepts; returns how many. In place:
// a vector is stored at or before where it was read.
template <class Keep>
std::size_t Compact(float* HWY_RESTRICT values, float* HWY_RESTRICT weights, std::size_t n, const Keep& keep) {
  const DF d;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; i += hn::Lanes(d)) {
    const VF value = hn::LoadU(d, values + i), weight = hn::LoadU(d, weights + i);
    const MF chosen = hn::And(keep(value), hn::FirstN(d, n - i));
    hn::CompressBlendedStore(weight, chosen, d, weights + kept);
    kept += hn::CompressBlendedStore(value, chosen, d, values + kept);
  }
  return kept;
}

float WeightedMedianSelect(float* HWY_RESTRICT values, float* HWY_RESTRICT weights, std::size_t n, float total) {
  const DF d;
  const DD dd;
  const float half = 0.5f * total;
  double below = 0;  // weight of the values already known to lie below the window
  while (n > 1) {
    const float a = values[0], b = values[n / 2], c = values[n - 1];
    const float pivot = std::max(std::min(a, b), std::min(std::max(a, b), c));  // median of three
    const VF at = hn::Set(d, pivot);
    // A value neither below nor above the pivot (a NaN) counts as equal, so a NaN pivot ends
    // the search.
    VD lessSum = hn::Zero(dd), equalSum = hn::Zero(dd);
    std::size_t lessCount = 0, greaterCount = 0;
    for (std::size_t i = 0; i < n; i += hn::Lanes(d)) {
      const MF valid = hn::FirstN(d, n - i);
      const VF value = hn::LoadU(d, values + i), weight = hn::LoadU(d, weights + i);
      const MF isLess = hn::And(hn::Lt(value, at), valid), isGreater = hn::And(hn::Gt(value, at), valid);
      lessSum = hn::Add(lessSum, hn::PromoteTo(dd, hn::IfThenElseZero(isLess, weight)));
      const MF isEqual = hn::AndNot(hn::Or(isLess, isGreater), valid);
      equalSum = hn::Add(equalSum, hn::PromoteTo(dd, hn::IfThenElseZero(isEqual, weight)));
      lessCount += hn::CountTrue(d, isLess);
      greaterCount += hn::CountTrue(d, isGreater);
    }
    const double lessWeight = hn::GetLane(hn::SumOfLanes(dd, lessSum));
    const double equalWeight = hn::GetLane(hn::SumOfLanes(dd, equalSum));
    if (below + lessWeight >= half && lessCount > 0) {
      n = Compact(values, weights, n, [&](VF v) { return hn::Lt(v, at); });  // half is reached below
    } else if (below + lessWeight + equalWeight >= half || greaterCount == 0) {
      return pivot;
    } else {
      below += lessWeight + equalWeight;
      n = Compact(values, weights, n, [&](VF v) { return hn::Gt(v, at); });
    }
  }
  return values[0];
}

}  // namespace HWY_NAMESPACE
}  // namespace lfcam::edof
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam::edof {

HWY_EXPORT(WeightedMedianSelect);

float weightedMedianSelect(float* values, float* weights, std::size_t n, float total) {
  return HWY_DYNAMIC_DISPATCH(WeightedMedianSelect)(values, weights, n, total);
}

}  // namespace lfcam::edof
#endif  // HWY_ONCE
