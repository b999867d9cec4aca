// Highway row kernels of shift_and_add_rows.hpp. foreach_target.h compiles this file once per
// instruction set; HWY_DYNAMIC_DISPATCH picks one on the first call.
#include "render/shift_and_add_rows.hpp"

#include <algorithm>
#include <cstddef>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "render/shift_and_add_rows.cpp"
#include <hwy/cache_control.h>
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// Columns x with both horizontal taps inside the view are the vector loop; at most one column on
// either side has a single tap, and the last partial vector is done one lane at a time.
void AccumulateBilinearRow(float* HWY_RESTRICT accumulator, const float* row0, const float* row1, int whole, float c00,
                           float c01, float c10, float c11, int ns, const float* nextRow) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  const int interiorBegin = std::max(0, -whole), interiorEnd = std::min(ns, ns - 1 - whole);
  // Single-tap edges: the right tap alone at source column 0, the left tap alone at ns - 1. They
  // come after the interior, when the rows are in L1: read first, a row's last element is a miss
  // at full memory latency, ahead of the prefetcher (measured: a quarter of this kernel's time).
  const auto edges = [&] {
    if (const int x = -1 - whole; x >= 0 && x < ns) accumulator[x] += c01 * row0[0] + c11 * row1[0];
    if (const int x = ns - 1 - whole; x >= 0 && x < ns && x >= interiorEnd)
      accumulator[x] += c00 * row0[ns - 1] + c10 * row1[ns - 1];
  };
  if (interiorBegin >= interiorEnd) return edges();

  // From here on, pointers start at the first interior column's source.
  const float* source0 = row0 + (interiorBegin + whole);
  const float* source1 = row1 + (interiorBegin + whole);
  float* interior = accumulator + interiorBegin;
  const int count = interiorEnd - interiorBegin;
  // The row the next call will read, fetched while this one computes (hardware prefetchers lose
  // these short row runs: measured, a third fewer samples in this kernel). Without one, a
  // harmless prefetch of a row already in cache.
  const float* ahead = nextRow ? nextRow + (interiorBegin + whole) : source0;
  int x = 0;
  const auto k00 = hn::Set(d, c00), k01 = hn::Set(d, c01);
  // One prefetch per 64-byte line: the vectors of a line are one step of the loop.
  const int step = std::max(1, 16 / lanes) * lanes;
  if (c10 == 0.0f && c11 == 0.0f) {
    // One source row (integer vertical shift, or the other row outside the view): half the loads.
    const auto vectorAt = [&](int k) {
      auto sum = hn::MulAdd(k00, hn::LoadU(d, source0 + k), hn::LoadU(d, interior + k));
      hn::StoreU(hn::MulAdd(k01, hn::LoadU(d, source0 + k + 1), sum), d, interior + k);
    };
    for (; x + step <= count; x += step) {
      hwy::Prefetch(ahead + x);
      for (int k = x; k < x + step; k += lanes) vectorAt(k);
    }
    for (; x + lanes <= count; x += lanes) vectorAt(x);
    for (; x < count; ++x) interior[x] += c00 * source0[x] + c01 * source0[x + 1];
    return edges();
  }
  // Each tap one fused multiply-add onto the accumulator: four per vector, no separate adds.
  const auto k10 = hn::Set(d, c10), k11 = hn::Set(d, c11);
  const auto vectorAt = [&](int k) {
    auto sum = hn::MulAdd(k00, hn::LoadU(d, source0 + k), hn::LoadU(d, interior + k));
    sum = hn::MulAdd(k01, hn::LoadU(d, source0 + k + 1), sum);
    sum = hn::MulAdd(k10, hn::LoadU(d, source1 + k), sum);
    hn::StoreU(hn::MulAdd(k11, hn::LoadU(d, source1 + k + 1), sum), d, interior + k);
  };
  for (; x + step <= count; x += step) {
    hwy::Prefetch(ahead + x);
    for (int k = x; k < x + step; k += lanes) vectorAt(k);
  }
  for (; x + lanes <= count; x += lanes) vectorAt(x);
  for (; x < count; ++x)
    interior[x] += (c00 * source0[x] + c01 * source0[x + 1]) + (c10 * source1[x] + c11 * source1[x + 1]);
  edges();
}

void AccumulateBilinearRows(float* HWY_RESTRICT accumulator, const float* plane, int ns, int nt, int y0, int y1,
                            int wholeX, float ax0, float ax1, int wholeY, float top, float bottom,
                            const float* nextPass) {
  for (int y = y0; y < y1; ++y) {
    const VerticalTaps taps = verticalTaps(y, wholeY, top, bottom, nt);
    if (taps.c0 == 0.0f) continue;
    // The row the next row reads; on the last, the first row of the next pass, so that the pass
    // does not start on a cold stream.
    const float* next = y + 1 == y1 ? nextPass : taps.row1 + 1 < nt ? plane + std::size_t(taps.row1 + 1) * ns : nullptr;
    AccumulateBilinearRow(accumulator + std::size_t(y - y0) * ns, plane + std::size_t(taps.row0) * ns,
                          plane + std::size_t(taps.row1) * ns, wholeX, taps.c0 * ax0, taps.c0 * ax1, taps.c1 * ax0,
                          taps.c1 * ax1, ns, next);
  }
}

void MultiplyRows(float* HWY_RESTRICT out, const float* HWY_RESTRICT a, const float* HWY_RESTRICT b, int count) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  int i = 0;
  for (; i + lanes <= count; i += lanes) hn::StoreU(hn::Mul(hn::LoadU(d, a + i), hn::LoadU(d, b + i)), d, out + i);
  for (; i < count; ++i) out[i] = a[i] * b[i];
}

void NormaliseRow(float* HWY_RESTRICT out, const float* HWY_RESTRICT sum, const float* HWY_RESTRICT weight, int count) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  const auto zero = hn::Zero(d);
  int i = 0;
  for (; i + lanes <= count; i += lanes) {
    const auto w = hn::LoadU(d, weight + i);
    hn::StoreU(hn::IfThenElseZero(w > zero, hn::Div(hn::LoadU(d, sum + i), w)), d, out + i);
  }
  for (; i < count; ++i) out[i] = weight[i] > 0 ? sum[i] / weight[i] : 0.0f;
}

}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {

HWY_EXPORT(AccumulateBilinearRow);
HWY_EXPORT(AccumulateBilinearRows);
HWY_EXPORT(MultiplyRows);
HWY_EXPORT(NormaliseRow);

void accumulateBilinearRow(float* accumulator, const float* row0, const float* row1, int whole, float c00, float c01,
                           float c10, float c11, int ns, const float* nextRow) {
  HWY_DYNAMIC_DISPATCH(AccumulateBilinearRow)(accumulator, row0, row1, whole, c00, c01, c10, c11, ns, nextRow);
}

void accumulateBilinearRows(float* accumulator, const float* plane, int ns, int nt, int y0, int y1, int wholeX,
                            float ax0, float ax1, int wholeY, float top, float bottom, const float* nextPass) {
  HWY_DYNAMIC_DISPATCH(AccumulateBilinearRows)
  (accumulator, plane, ns, nt, y0, y1, wholeX, ax0, ax1, wholeY, top, bottom, nextPass);
}

void multiplyRows(float* out, const float* a, const float* b, int count) {
  HWY_DYNAMIC_DISPATCH(MultiplyRows)(out, a, b, count);
}

void normaliseRow(float* out, const float* sum, const float* weight, int count) {
  HWY_DYNAMIC_DISPATCH(NormaliseRow)(out, sum, weight, count);
}

}  // namespace lfcam
#endif  // HWY_ONCE
