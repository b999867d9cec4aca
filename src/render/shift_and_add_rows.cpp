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

// sum[x] += the taps of rows[0, K) for x in [from, to), where every row has both taps inside.
template <int K>
void AddInterior(float* HWY_RESTRICT sum, const ShiftedRow* rows, int from, int to) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  const float* source[K];
  float c0[K], c1[K];
  for (int k = 0; k < K; ++k) source[k] = rows[k].row + rows[k].whole, c0[k] = rows[k].c0, c1[k] = rows[k].c1;
  int x = from;
  for (; x + lanes <= to; x += lanes) {
    auto total = hn::LoadU(d, sum + x);
    for (int k = 0; k < K; ++k) {
      total = hn::MulAdd(hn::Set(d, c0[k]), hn::LoadU(d, source[k] + x), total);
      total = hn::MulAdd(hn::Set(d, c1[k]), hn::LoadU(d, source[k] + x + 1), total);
    }
    hn::StoreU(total, d, sum + x);
  }
  for (; x < to; ++x) {
    float total = sum[x];
    for (int k = 0; k < K; ++k) total += c0[k] * source[k][x] + c1[k] * source[k][x + 1];
    sum[x] = total;
  }
}

// AddInterior<count>, for count in [1, maxRowsPerPass].
template <std::size_t... K>
void AddInteriorOf(int count, float* sum, const ShiftedRow* rows, int from, int to, std::index_sequence<K...>) {
  using Add = void (*)(float*, const ShiftedRow*, int, int);
  static constexpr Add add[] = {&AddInterior<int(K) + 1>...};
  add[count - 1](sum, rows, from, to);
}

// One pass of at most maxRowsPerPass rows. Row k has both taps inside for output columns
// [-whole, ns - 1 - whole) within [0, ns); the columns common to all are one pass, the rest of
// each row's own, and its at most two single-tap columns, row by row.
void AddRowsOnce(float* HWY_RESTRICT sum, const ShiftedRow* rows, int count, int ns) {
  int from = 0, to = ns;
  for (int k = 0; k < count; ++k) from = std::max(from, -rows[k].whole), to = std::min(to, ns - 1 - rows[k].whole);
  if (from < to) {
    AddInteriorOf(count, sum, rows, from, to, std::make_index_sequence<maxRowsPerPass>());
  } else {
    from = to = ns;  // no column common to all: each row's own below
  }
  for (int k = 0; k < count; ++k) {
    const ShiftedRow& row = rows[k];
    const int begin = std::max(0, -row.whole), end = std::min(ns, ns - 1 - row.whole);
    if (begin < std::min(from, end)) AddInterior<1>(sum, &row, begin, std::min(from, end));
    if (std::max(to, begin) < end) AddInterior<1>(sum, &row, std::max(to, begin), end);
    // The right tap alone at source column 0, the left tap alone at ns - 1.
    if (const int x = -1 - row.whole; x >= 0 && x < ns) sum[x] += row.c1 * row.row[0];
    if (const int x = ns - 1 - row.whole; x >= 0 && x < ns && x >= end) sum[x] += row.c0 * row.row[ns - 1];
  }
}

void AddShiftedRows(float* HWY_RESTRICT sum, const ShiftedRow* rows, int count, int ns) {
  // Passes of balanced sizes (15 rows: 8 and 7).
  const int passes = (count + maxRowsPerPass - 1) / maxRowsPerPass;
  for (int pass = 0, begin = 0; pass < passes; ++pass) {
    const int end = count * (pass + 1) / passes;
    AddRowsOnce(sum, rows + begin, end - begin, ns);
    begin = end;
  }
}

void AddVerticalTaps(float* HWY_RESTRICT accumulator, const float* HWY_RESTRICT upper, const float* HWY_RESTRICT lower,
                     float top, float bottom, int count) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  const auto kTop = hn::Set(d, top), kBottom = hn::Set(d, bottom);
  int i = 0;
  for (; i + lanes <= count; i += lanes) {
    const auto sum = hn::MulAdd(kTop, hn::LoadU(d, upper + i), hn::LoadU(d, accumulator + i));
    hn::StoreU(hn::MulAdd(kBottom, hn::LoadU(d, lower + i), sum), d, accumulator + i);
  }
  for (; i < count; ++i) accumulator[i] += top * upper[i] + bottom * lower[i];
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

HWY_EXPORT(AddShiftedRows);
HWY_EXPORT(AddVerticalTaps);
HWY_EXPORT(MultiplyRows);
HWY_EXPORT(NormaliseRow);

void addShiftedRows(float* sum, const ShiftedRow* rows, int count, int ns) {
  HWY_DYNAMIC_DISPATCH(AddShiftedRows)(sum, rows, count, ns);
}

void addVerticalTaps(float* accumulator, const float* upper, const float* lower, float top, float bottom, int count) {
  HWY_DYNAMIC_DISPATCH(AddVerticalTaps)(accumulator, upper, lower, top, bottom, count);
}

void multiplyRows(float* out, const float* a, const float* b, int count) {
  HWY_DYNAMIC_DISPATCH(MultiplyRows)(out, a, b, count);
}

void normaliseRow(float* out, const float* sum, const float* weight, int count) {
  HWY_DYNAMIC_DISPATCH(NormaliseRow)(out, sum, weight, count);
}

}  // namespace lfcam
#endif  // HWY_ONCE
