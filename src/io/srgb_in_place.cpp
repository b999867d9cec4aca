// srgbFromLinear over many values (image_io.hpp) in Highway: the same formula in double lanes,
// x^(1/2.4) as exp(log(x) / 2.4), whose error in double is far below a float's rounding step, so
// the floats are srgbFromLinear's (all of 20 million random values in tests/srgb_test.cpp; one could
// round the other way only where the exact value lies within about 1e-15 of a rounding boundary);
// libm's pow, one value at a time, was half of depth's set-up. foreach_target.h compiles this
// file once per instruction set; HWY_DYNAMIC_DISPATCH picks one on the first call.
#include <algorithm>
#include <cstddef>
#include <span>

#include "lfcam/io/image_io.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "io/srgb_in_place.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
// After highway.h, once per target like it.
#include <hwy/contrib/math/math-inl.h>

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

using DD = hn::ScalableTag<double>;
using DF = hn::Rebind<float, DD>;

HWY_INLINE hn::Vec<DF> Encoded(DD dd, DF df, hn::Vec<DF> linear) {
  const auto x = hn::PromoteTo(dd, linear);
  const auto low = hn::Le(x, hn::Set(dd, 0.0031308));
  // At or below the toe the logarithm is not needed, and 1 keeps it finite there; NaN stays NaN.
  const auto safe = hn::IfThenElse(low, hn::Set(dd, 1.0), x);
  const auto power = hn::CallExp(dd, hn::Mul(hn::CallLog(dd, safe), hn::Set(dd, 1.0 / 2.4)));
  const auto curve = hn::Sub(hn::Mul(hn::Set(dd, 1.055), power), hn::Set(dd, 0.055));
  const auto encoded = hn::IfThenElse(low, hn::Mul(x, hn::Set(dd, 12.92)), curve);
  return hn::DemoteTo(df, hn::IfThenElse(hn::IsNaN(x), x, encoded));
}

void SrgbFromLinearInPlace(float* HWY_RESTRICT values, std::size_t count) {
  const DD dd;
  const DF df;
  const std::size_t lanes = hn::Lanes(dd);
  std::size_t i = 0;
  for (; i + lanes <= count; i += lanes) hn::StoreU(Encoded(dd, df, hn::LoadU(df, values + i)), df, values + i);
  if (i == count) return;
  // The last partial vector, through a full one.
  HWY_ALIGN float last[hn::MaxLanes(df)] = {};
  std::copy(values + i, values + count, last);
  hn::Store(Encoded(dd, df, hn::Load(df, last)), df, last);
  std::copy(last, last + (count - i), values + i);
}

}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {

HWY_EXPORT(SrgbFromLinearInPlace);

void srgbFromLinear(std::span<float> values) {
  HWY_DYNAMIC_DISPATCH(SrgbFromLinearInPlace)(values.data(), values.size());
}

}  // namespace lfcam
#endif  // HWY_ONCE
