// The row kernel of disagreement_row.hpp in Highway; foreach_target.h compiles this file once per
// instruction set and HWY_DYNAMIC_DISPATCH picks one on the first call. Positions are taken from
// each lens's centre (whole column apart), so that float keeps them to a small fraction of a pixel.
#include "focused/disagreement_row.hpp"

#include <algorithm>
#include <cmath>

#include "core/bilinear.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "focused/disagreement_row.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace lfcam::focused_detail {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;

// Adds the samples of lens `lens` to the sums of the pixels of row py in [begin, end) its disc
// covers (pixel p's at p - begin).
void AddLens(const Image& grey, const LensesByRow& lenses, std::uint32_t lens, const FocusedPhotoFrame& frame, double v,
             double sign, int py, int begin, int end, DisagreementSums& sums) {
  const DF df;
  const DI di;
  const int lanes = int(hn::Lanes(df)), width = grey.width(), height = grey.height();
  const auto [cx, cy] = lenses.centre(lens);
  const double disc = lenses.discRadius(), ey = frame.imagePoint(0, py + 0.5)[1] - cy;
  const double step = frame.imagePxPerPixel, left = frame.originPx[0];
  // Most lenses of a row miss a short span: left before the square root.
  if (ey * ey >= disc * disc || cx + disc < left + (begin - 1) * step || cx - disc > left + (end + 1) * step) return;
  const double half = std::sqrt(disc * disc - ey * ey);
  const int p0 = std::max(begin, int(std::floor((cx - half - left) / step - 0.5)));
  const int p1 = std::min(end, int(std::ceil((cx + half - left) / step - 0.5)) + 1);
  if (p0 >= p1) return;
  // S's row is the same along the span: bilinearSample's two rows and weight.
  const double y = std::clamp(cy + sign * ey / v - 0.5, 0.0, double(height - 1));
  const int y0 = std::min(int(y), std::max(height - 2, 0)), y1 = std::min(y0 + 1, height - 1);
  const VF fy = hn::Set(df, float(y - y0));
  const float* row0 = grey.plane(0) + std::size_t(y0) * width;
  const float* row1 = grey.plane(0) + std::size_t(y1) * width;
  // Columns from xBase: S's x less xBase is cx - xBase - 0.5 + sign ex / v, at most a disc away.
  const int xBase = int(std::floor(cx));
  const VF centre = hn::Set(df, float(cx - xBase - 0.5)), slope = hn::Set(df, float(sign / v));
  const VF lowest = hn::Set(df, float(-xBase)), highest = hn::Set(df, float(width - 1 - xBase));
  const VF lastLeft = hn::Set(df, float(std::max(width - 2, 0) - xBase));
  const auto base = hn::Set(di, xBase), lastColumn = hn::Set(di, width - 1);
  const VF ey2 = hn::Set(df, float(ey * ey)), inverseDisc2 = hn::Set(df, float(1 / (disc * disc)));
  const VF one = hn::Set(df, 1.0f), firstEx = hn::Set(df, float(left + (p0 + 0.5) * step - cx));
  const VF stepV = hn::Set(df, float(step)), count = hn::Set(df, float(p1 - p0));
  for (int p = p0; p < p1; p += lanes) {
    const VF k = hn::Iota(df, float(p - p0));
    const VF ex = hn::MulAdd(k, stepV, firstEx);
    const VF r2 = hn::MulAdd(ex, ex, ey2);
    const auto in = hn::And(hn::Lt(hn::Mul(r2, inverseDisc2), one), hn::Lt(k, count));
    const VF x = hn::Min(hn::Max(hn::MulAdd(ex, slope, centre), lowest), highest);
    const VF x0 = hn::Min(hn::Floor(x), lastLeft);
    const VF fx = hn::Sub(x, x0);
    const auto column0 = hn::Add(hn::ConvertTo(di, x0), base);
    const auto column1 = hn::Min(hn::Add(column0, hn::Set(di, 1)), lastColumn);
    const VF a = hn::GatherIndex(df, row0, column0), b = hn::GatherIndex(df, row0, column1);
    const VF c = hn::GatherIndex(df, row1, column0), e = hn::GatherIndex(df, row1, column1);
    const VF top = hn::MulAdd(fx, hn::Sub(b, a), a), bottom = hn::MulAdd(fx, hn::Sub(e, c), c);
    const VF value = hn::MulAdd(fy, hn::Sub(bottom, top), top);
    const VF weight = hn::IfThenElseZero(in, hn::NegMulAdd(r2, inverseDisc2, one));
    const VF weighted = hn::Mul(weight, value);
    const std::size_t at = std::size_t(p - begin);
    float* sw = sums.weight.data() + at;
    float* s1 = sums.value.data() + at;
    float* s2 = sums.square.data() + at;
    float* n = sums.seen.data() + at;
    hn::StoreU(hn::Add(hn::LoadU(df, sw), weight), df, sw);
    hn::StoreU(hn::Add(hn::LoadU(df, s1), weighted), df, s1);
    hn::StoreU(hn::MulAdd(weighted, value, hn::LoadU(df, s2)), df, s2);
    hn::StoreU(hn::Add(hn::LoadU(df, n), hn::IfThenElseZero(in, one)), df, n);
  }
}

void DisagreementRow(const Image& grey, const LensesByRow& lenses, const FocusedPhotoFrame& frame, double v,
                     double sign, int py, int begin, int end, DisagreementSums& sums, float* raw, float* seen) {
  const std::size_t padded = std::size_t(end - begin) + hn::Lanes(DF());
  for (std::vector<float>* sum : {&sums.weight, &sums.value, &sums.square, &sums.seen}) sum->assign(padded, 0.0f);
  for (const std::uint32_t lens : lenses.row(py)) AddLens(grey, lenses, lens, frame, v, sign, py, begin, end, sums);
  for (std::size_t k = 0; k < std::size_t(end - begin); ++k) {
    const bool two = sums.seen[k] >= 2;
    const float mean = sums.value[k] / sums.weight[k];
    raw[k] = two ? std::max(0.0f, sums.square[k] / sums.weight[k] - mean * mean) : 0.0f;
    seen[k] = two ? 1.0f : 0.0f;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace lfcam::focused_detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam::focused_detail {

HWY_EXPORT(DisagreementRow);

LensesByRow::LensesByRow(const MicroImageViews& views, const FocusedPhotoFrame& frame, double discRadius, int firstRow,
                         int endRow)
    : discRadius_(discRadius),
      firstRow_(firstRow),
      centres_(&views.centres()),
      starts_(std::size_t(std::max(endRow - firstRow, 0)) + 2, 0) {
  const double step = frame.imagePxPerPixel, top = frame.originPx[1];
  // The rows py in [firstRow, endRow) whose centre's y, top + (py + 0.5) step, lies within the disc,
  // less firstRow.
  const auto rowsOf = [&](const std::array<double, 2>& c) {
    return std::array<int, 2>{std::max(firstRow, int(std::floor((c[1] - discRadius - top) / step - 0.5))) - firstRow,
                              std::min(endRow - 1, int(std::ceil((c[1] + discRadius - top) / step - 0.5))) - firstRow};
  };
  // Only the lattice rows that can reach those rows.
  const auto forEachLens = [&](auto&& visit) {
    const int columns = views.columns();
    for (std::size_t j = 0; j < views.rowSpans().size(); ++j) {
      const auto [least, greatest] = views.rowSpans()[j];
      if (greatest + discRadius < top + (firstRow - 1) * step || least - discRadius > top + (endRow + 1) * step)
        continue;
      for (std::uint32_t lens = std::uint32_t(j * columns); lens < std::uint32_t((j + 1) * columns); ++lens) {
        const auto [first, last] = rowsOf((*centres_)[lens]);
        visit(lens, first, last);
      }
    }
  };
  forEachLens([&](std::uint32_t, int first, int last) {
    for (int k = first; k <= last; ++k) ++starts_[std::size_t(k) + 2];
  });
  for (std::size_t k = 2; k < starts_.size(); ++k) starts_[k] += starts_[k - 1];
  lenses_.resize(starts_.back());
  forEachLens([&](std::uint32_t lens, int first, int last) {
    for (int k = first; k <= last; ++k) lenses_[starts_[std::size_t(k) + 1]++] = lens;
  });
}

void disagreementRow(const Image& grey, const LensesByRow& lenses, const FocusedPhotoFrame& frame, double v,
                     double sign, int py, int begin, int end, DisagreementSums& sums, float* raw, float* seen) {
  HWY_DYNAMIC_DISPATCH(DisagreementRow)(grey, lenses, frame, v, sign, py, begin, end, sums, raw, seen);
}

void disagreementRowReference(const Image& grey, const MicroImageViews& views, const FocusedPhotoFrame& frame, double v,
                              int py, int begin, int end, float* raw, float* seen) {
  for (int px = begin; px < end; ++px) {
    const auto q = frame.imagePoint(px + 0.5, py + 0.5);
    double sw = 0, s1 = 0, s2 = 0;
    int visits = 0;
    views.forEach(q[0], q[1], v, [&](const MicroImageSample& s) {
      const double value = bilinearSample(grey.plane(0), grey.width(), grey.height(), s.x - 0.5, s.y - 0.5);
      const double weight = 1 - s.rho * s.rho;
      sw += weight;
      s1 += weight * value;
      s2 += weight * value * value;
      ++visits;
    });
    raw[px - begin] = visits >= 2 ? float(std::max(0.0, s2 / sw - (s1 / sw) * (s1 / sw))) : 0.0f;
    seen[px - begin] = visits >= 2 ? 1.0f : 0.0f;
  }
}

}  // namespace lfcam::focused_detail
#endif  // HWY_ONCE
