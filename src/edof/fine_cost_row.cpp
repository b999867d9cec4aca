// The row kernel of fine_cost_row.hpp in Highway, lanes of doubles for the positions and the
// terms, as the scalar reference computes them, with the float lanes of the same count for the
// samples (gathered: each pixel reads its own position). foreach_target.h compiles this file once
// per instruction set; HWY_DYNAMIC_DISPATCH picks one on the first call. The file is compiled
// without contracting a * b + c into fused multiply-adds (CMakeLists.txt), which the targets
// with FMA would otherwise do, and which the scalar reference, built for baseline x86-64, does not.
#include "edof/fine_cost_row.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "core/bilinear.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "edof/fine_cost_row.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace lfcam::edof {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

using DD = hn::ScalableTag<double>;
using DF = hn::Rebind<float, DD>;
using DI = hn::Rebind<std::int32_t, DD>;
using VD = hn::Vec<DD>;
using VF = hn::Vec<DF>;

// bilinearSample (core/bilinear.hpp) of each lane's position: clamped, its whole part (in double,
// exact) limited to the last but one column or row, the fraction rounded to float.
VF Sample(const float* HWY_RESTRICT plane, int ns, int nt, VD x, VD y) {
  const DD dd;
  const DF df;
  const DI di;
  x = hn::Min(hn::Max(x, hn::Zero(dd)), hn::Set(dd, double(ns - 1)));
  y = hn::Min(hn::Max(y, hn::Zero(dd)), hn::Set(dd, double(nt - 1)));
  const VD x0 = hn::Min(hn::Floor(x), hn::Set(dd, double(std::max(ns - 2, 0))));
  const VD y0 = hn::Min(hn::Floor(y), hn::Set(dd, double(std::max(nt - 2, 0))));
  const VF fx = hn::DemoteTo(df, hn::Sub(x, x0)), fy = hn::DemoteTo(df, hn::Sub(y, y0));
  const auto column0 = hn::DemoteTo(di, x0), row0 = hn::DemoteTo(di, y0);
  const auto column1 = hn::Min(hn::Add(column0, hn::Set(di, 1)), hn::Set(di, ns - 1));
  const auto row1 = hn::Min(hn::Add(row0, hn::Set(di, 1)), hn::Set(di, nt - 1));
  const auto top0 = hn::Mul(row0, hn::Set(di, ns)), bottom0 = hn::Mul(row1, hn::Set(di, ns));
  const VF a = hn::GatherIndex(df, plane, hn::Add(top0, column0));
  const VF b = hn::GatherIndex(df, plane, hn::Add(top0, column1));
  const VF c = hn::GatherIndex(df, plane, hn::Add(bottom0, column0));
  const VF e = hn::GatherIndex(df, plane, hn::Add(bottom0, column1));
  const VF top = hn::Add(a, hn::Mul(fx, hn::Sub(b, a))), bottom = hn::Add(c, hn::Mul(fx, hn::Sub(e, c)));
  return hn::Add(top, hn::Mul(fy, hn::Sub(bottom, top)));
}

// shift - floor(shift).
VD Fraction(VD shift) { return hn::Sub(shift, hn::Floor(shift)); }

// interpolationNoiseLoss (interpolation_terms.hpp) from the fractions of both shifts.
VD NoiseLoss(const ViewNoise& noise, VD fx, VD fy) {
  const DD dd;
  const VD one = hn::Set(dd, 1.0), two = hn::Set(dd, 2.0), correlated = hn::Set(dd, 1 - noise.neighbourCorrelation);
  const auto kept = [&](VD f) { return hn::Sub(one, hn::Mul(hn::Mul(hn::Mul(two, f), hn::Sub(one, f)), correlated)); };
  return hn::Mul(hn::Set(dd, noise.variance), hn::Sub(one, hn::Mul(kept(fx), kept(fy))));
}

// interpolationBlur (interpolation_terms.hpp) from the fraction of a shift.
VD Blur(VD f) {
  const DD dd;
  return hn::Mul(hn::Mul(hn::Set(dd, 0.5), f), hn::Sub(hn::Set(dd, 1.0), f));
}

// Pixels [x, x + lanes) of the row.
void CostLanes(const FineCostViews& views, int y, int x, const float* HWY_RESTRICT disparity, double offset,
               float* HWY_RESTRICT reference, float* const* out) {
  const DD dd;
  const DF df;
  const int ns = views.ns, nt = views.nt, channels = views.channels, lanes = int(hn::Lanes(df));
  const std::size_t subsets = views.viewsIn.size(), p = std::size_t(y) * ns + x;
  const bool locking = views.locking > 0, noisy = views.noise.variance > 0;
  const VD column = hn::Iota(dd, double(x)), row = hn::Set(dd, double(y));
  const VD d = hn::Add(hn::PromoteTo(dd, hn::LoadU(df, disparity + x)), hn::Set(dd, offset));
  // Each view's shift (-uc d, -vc d) and its position (x, y) + the shift, as the reference computes them.
  const auto shiftX = [&](std::size_t i) { return hn::Mul(hn::Set(dd, -views.uc[i]), d); };
  const auto shiftY = [&](std::size_t i) { return hn::Mul(hn::Set(dd, -views.vc[i]), d); };
  const auto positionX = [&](std::size_t i) { return hn::Sub(column, hn::Mul(hn::Set(dd, views.uc[i]), d)); };
  const auto positionY = [&](std::size_t i) { return hn::Sub(row, hn::Mul(hn::Set(dd, views.vc[i]), d)); };
  const VD referenceLoss = noisy ? NoiseLoss(views.noise, Fraction(shiftX(0)), Fraction(shiftY(0))) : hn::Zero(dd);
  for (int c = 0; c < channels; ++c)
    hn::StoreU(Sample(views.planes[c], ns, nt, positionX(0), positionY(0)), df, reference + c * lanes);
  const VD xx = locking ? hn::PromoteTo(dd, hn::LoadU(df, views.xx + p)) : hn::Zero(dd);
  const VD yy = locking ? hn::PromoteTo(dd, hn::LoadU(df, views.yy + p)) : hn::Zero(dd);
  const VD xy = locking ? hn::PromoteTo(dd, hn::LoadU(df, views.xy + p)) : hn::Zero(dd);
  VF sums[kMaxCostSubsets];
  for (VF& sum : sums) sum = hn::Zero(df);
  for (std::size_t i = 1; i < views.uc.size(); ++i) {
    const VD sampleX = positionX(i), sampleY = positionY(i);
    VF squares = hn::Zero(df);
    for (int c = 0; c < channels; ++c) {
      const VF difference = hn::Sub(Sample(views.planes[i * channels + c], ns, nt, sampleX, sampleY),
                                    hn::LoadU(df, reference + c * lanes));
      squares = hn::Add(squares, hn::Mul(difference, difference));
    }
    VF bias = hn::Zero(df), loss = hn::Zero(df);
    if (locking || noisy) {
      const VD fx = Fraction(shiftX(i)), fy = Fraction(shiftY(i));
      if (locking) {
        const VD bx = Blur(fx), by = Blur(fy);
        const VD sum =
            hn::Add(hn::Add(hn::Mul(hn::Mul(bx, bx), xx), hn::Mul(hn::Mul(by, by), yy)), hn::Mul(hn::Mul(bx, by), xy));
        bias = hn::DemoteTo(df, hn::Mul(hn::Set(dd, views.locking), sum));
      }
      if (noisy) loss = hn::DemoteTo(df, hn::Add(referenceLoss, NoiseLoss(views.noise, fx, fy)));
    }
    const VF term = hn::Add(hn::Sub(squares, bias), loss);
    for (std::size_t j = 0; j < subsets; ++j)
      if ((views.subsets[i] >> j) & 1) sums[j] = hn::Add(sums[j], term);
  }
  for (std::size_t j = 0; j < subsets; ++j)
    hn::StoreU(hn::Div(sums[j], hn::Set(df, float(views.viewsIn[j]))), df, out[j] + x);
}

void FineCostRow(const FineCostViews& views, int y, const float* disparity, double offset, float* const* out) {
  const DF df;
  const int lanes = int(hn::Lanes(df)), ns = views.ns;
  if (ns < lanes) return fineCostRowReference(views, y, disparity, offset, out);
  std::vector<float> reference(std::size_t(views.channels) * lanes);
  // The last lanes end at the row's end, overlapping the lanes before: each pixel's cost is its own.
  for (int x = 0; x < ns; x += lanes)
    CostLanes(views, y, std::min(x, ns - lanes), disparity, offset, reference.data(), out);
}

}  // namespace HWY_NAMESPACE
}  // namespace lfcam::edof
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam::edof {

HWY_EXPORT(FineCostRow);

void fineCostRow(const FineCostViews& views, int y, const float* disparity, double offset, float* const* out) {
  HWY_DYNAMIC_DISPATCH(FineCostRow)(views, y, disparity, offset, out);
}

void fineCostRowReference(const FineCostViews& views, int y, const float* disparity, double offset, float* const* out) {
  const int ns = views.ns, nt = views.nt, channels = views.channels;
  const std::size_t subsets = views.viewsIn.size();
  const double referenceUc = views.uc[0], referenceVc = views.vc[0];
  std::vector<float> reference(channels);
  for (int x = 0; x < ns; ++x) {
    const std::size_t p = std::size_t(y) * ns + x;
    const double d = disparity[x] + offset;
    const double referenceLoss = interpolationNoiseLoss(views.noise, -referenceUc * d, -referenceVc * d);
    for (int c = 0; c < channels; ++c)
      reference[c] = bilinearSample(views.planes[c], ns, nt, x - referenceUc * d, double(y) - referenceVc * d);
    float sums[kMaxCostSubsets] = {};
    for (std::size_t i = 1; i < views.uc.size(); ++i) {
      const double uc = views.uc[i], vc = views.vc[i];
      float squares = 0;
      for (int c = 0; c < channels; ++c) {
        const float difference =
            bilinearSample(views.planes[i * channels + c], ns, nt, x - uc * d, double(y) - vc * d) - reference[c];
        squares += difference * difference;
      }
      // The interpolation-bias term (cost_volume.cpp's correspondenceCost).
      float bias = 0;
      if (views.locking > 0) {
        const double bx = interpolationBlur(-uc * d), by = interpolationBlur(-vc * d);
        bias = float(views.locking * (bx * bx * views.xx[p] + by * by * views.yy[p] + bx * by * views.xy[p]));
      }
      const float loss = float(referenceLoss + interpolationNoiseLoss(views.noise, -uc * d, -vc * d));
      for (std::size_t j = 0; j < subsets; ++j)
        if ((views.subsets[i] >> j) & 1) sums[j] += squares - bias + loss;
    }
    for (std::size_t j = 0; j < subsets; ++j) out[j][x] = sums[j] / views.viewsIn[j];
  }
}

}  // namespace lfcam::edof
#endif  // HWY_ONCE
