// Highway row kernels of shift_and_add_rows.hpp. foreach_target.h compiles this file once per
// instruction set; HWY_DYNAMIC_DISPATCH picks one on the first call.
#include "render/shift_and_add_rows.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "render/shift_and_add_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// Rows added in one pass over sum, each with its two coefficients: a row of 9 views in one pass
// (on AVX2, with 16 registers, some coefficients are read from L1 instead).
constexpr int maxRowsPerPass = 9;

// accumulator[x] += top * above[x] + bottom * below[x] over [from, to).
void AddVertical(const OutputRow& out, const float* HWY_RESTRICT below, int from, int to) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  const auto top = hn::Set(d, out.top), bottom = hn::Set(d, out.bottom);
  int x = from;
  for (; x + lanes <= to; x += lanes) {
    const auto sum = hn::MulAdd(top, hn::LoadU(d, out.above + x), hn::LoadU(d, out.accumulator + x));
    hn::StoreU(hn::MulAdd(bottom, hn::LoadU(d, below + x), sum), d, out.accumulator + x);
  }
  for (; x < to; ++x) out.accumulator[x] += out.top * out.above[x] + out.bottom * below[x];
}

// The taps of rows[0, K) for x in [from, to), where every row has both taps inside: added to
// sum, or (kFinal: these are all of sum's taps there) stored in sum and the output row finished
// in the same loop, so that sum is not read back.
template <int K, bool kFinal>
void AddInterior(float* HWY_RESTRICT sum, const ShiftedRow* rows, int from, int to, const OutputRow* out) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  const float* source[K];
  float c0[K], c1[K];
  for (int k = 0; k < K; ++k) source[k] = rows[k].row + rows[k].whole, c0[k] = rows[k].c0, c1[k] = rows[k].c1;
  int x = from;
  for (; x + lanes <= to; x += lanes) {
    auto total = kFinal ? hn::Zero(d) : hn::LoadU(d, sum + x);
    for (int k = 0; k < K; ++k) {
      total = hn::MulAdd(hn::Set(d, c0[k]), hn::LoadU(d, source[k] + x), total);
      total = hn::MulAdd(hn::Set(d, c1[k]), hn::LoadU(d, source[k] + x + 1), total);
    }
    hn::StoreU(total, d, sum + x);
    if (kFinal && out) {
      const auto above = hn::LoadU(d, out->above + x), accumulator = hn::LoadU(d, out->accumulator + x);
      const auto partial = hn::MulAdd(hn::Set(d, out->top), above, accumulator);
      hn::StoreU(hn::MulAdd(hn::Set(d, out->bottom), total, partial), d, out->accumulator + x);
    }
  }
  for (; x < to; ++x) {
    float total = kFinal ? 0.0f : sum[x];
    for (int k = 0; k < K; ++k) total += c0[k] * source[k][x] + c1[k] * source[k][x + 1];
    sum[x] = total;
    if (kFinal && out) out->accumulator[x] += out->top * out->above[x] + out->bottom * total;
  }
}

// AddInterior<count, kFinal>, for count in [1, maxRowsPerPass].
template <bool kFinal, std::size_t... K>
void AddInteriorOf(int count, float* sum, const ShiftedRow* rows, int from, int to, const OutputRow* out,
                   std::index_sequence<K...>) {
  using Add = void (*)(float*, const ShiftedRow*, int, int, const OutputRow*);
  static constexpr Add add[] = {&AddInterior<int(K) + 1, kFinal>...};
  add[count - 1](sum, rows, from, to, out);
}

// The columns where every one of the rows has both taps inside: row k has them for output
// columns [-whole, ns - 1 - whole) within [0, ns). Empty: [ns, ns).
std::pair<int, int> CommonInterior(const ShiftedRow* rows, int count, int ns) {
  int from = 0, to = ns;
  for (int k = 0; k < count; ++k) from = std::max(from, -rows[k].whole), to = std::min(to, ns - 1 - rows[k].whole);
  return from < to ? std::pair(from, to) : std::pair(ns, ns);
}

// The taps of each row outside [from, to): the rest of its interior, and its at most two
// single-tap columns, row by row.
void AddOutside(float* HWY_RESTRICT sum, const ShiftedRow* rows, int count, int from, int to, int ns) {
  for (int k = 0; k < count; ++k) {
    const ShiftedRow& row = rows[k];
    const int begin = std::max(0, -row.whole), end = std::min(ns, ns - 1 - row.whole);
    if (begin < std::min(from, end)) AddInterior<1, false>(sum, &row, begin, std::min(from, end), nullptr);
    if (std::max(to, begin) < end) AddInterior<1, false>(sum, &row, std::max(to, begin), end, nullptr);
    // The right tap alone at source column 0, the left tap alone at ns - 1.
    if (const int x = -1 - row.whole; x >= 0 && x < ns) sum[x] += row.c1 * row.row[0];
    if (const int x = ns - 1 - row.whole; x >= 0 && x < ns && x >= end) sum[x] += row.c0 * row.row[ns - 1];
  }
}

void SumShiftedRows(float* HWY_RESTRICT sum, const ShiftedRow* rows, int count, int ns, const OutputRow* out) {
  const auto interior = std::make_index_sequence<maxRowsPerPass>();
  if (count >= 1 && count <= maxRowsPerPass) {
    // One pass: its common columns take no other tap, so they are stored and finished at once.
    const auto [from, to] = CommonInterior(rows, count, ns);
    std::fill(sum, sum + from, 0.0f);
    std::fill(sum + to, sum + ns, 0.0f);
    if (from < to) AddInteriorOf<true>(count, sum, rows, from, to, out, interior);
    AddOutside(sum, rows, count, from, to, ns);
    if (out) {
      AddVertical(*out, sum, 0, from);
      AddVertical(*out, sum, to, ns);
    }
    return;
  }
  // Passes of balanced sizes (15 rows: 8 and 7), each added to sum.
  std::fill(sum, sum + ns, 0.0f);
  const int passes = (count + maxRowsPerPass - 1) / maxRowsPerPass;
  for (int pass = 0, begin = 0; pass < passes; ++pass) {
    const int end = count * (pass + 1) / passes;
    const auto [from, to] = CommonInterior(rows + begin, end - begin, ns);
    if (from < to) AddInteriorOf<false>(end - begin, sum, rows + begin, from, to, nullptr, interior);
    AddOutside(sum, rows + begin, end - begin, from, to, ns);
    begin = end;
  }
  if (out) AddVertical(*out, sum, 0, ns);
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

HWY_EXPORT(SumShiftedRows);
HWY_EXPORT(MultiplyRows);
HWY_EXPORT(NormaliseRow);

void sumShiftedRows(float* sum, const ShiftedRow* rows, int count, int ns, const OutputRow* out) {
  HWY_DYNAMIC_DISPATCH(SumShiftedRows)(sum, rows, count, ns, out);
}

void multiplyRows(float* out, const float* a, const float* b, int count) {
  HWY_DYNAMIC_DISPATCH(MultiplyRows)(out, a, b, count);
}

void normaliseRow(float* out, const float* sum, const float* weight, int count) {
  HWY_DYNAMIC_DISPATCH(NormaliseRow)(out, sum, weight, count);
}

}  // namespace lfcam
#endif  // HWY_ONCE
