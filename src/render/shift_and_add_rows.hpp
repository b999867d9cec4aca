// The row kernels of the fast shift-and-add (refocus.cpp), in SIMD through Highway with run-time
// dispatch: each call runs the widest instruction set the CPU has (AVX-512, AVX2, SSE4, ...).
// Internal to the library.
#pragma once

#include <vector>

#include "lfcam/image.hpp"

namespace lfcam {

// One view's contribution to one output row, at a constant shift: for every output column x in
// [0, ns), with source column s = x + whole,
//   accumulator[x] += c00 row0[s] + c01 row0[s + 1] + c10 row1[s] + c11 row1[s + 1]
// where a tap whose column lies outside [0, ns) counts as 0 (the view ends there). row0 and row1
// are the two source rows of the vertical taps (they may be the same row when c10 = c11 = 0).
// nextRow, when not null, is the source row the next call will read: it is prefetched.
void accumulateBilinearRow(float* accumulator, const float* row0, const float* row1, int whole, float c00, float c01,
                           float c10, float c11, int ns, const float* nextRow = nullptr);

// The vertical taps of output row y for a view shifted by `whole` rows plus a fraction: rows
// y + whole and y + whole + 1 with coefficients top and bottom ((1 - fraction) and fraction, times
// any weight), a tap outside [0, nt) or of coefficient 0 dropped. A single live tap is always
// row0 (with row1 = row0 and c1 = 0), so that it is read once; none live: c0 = c1 = 0.
struct VerticalTaps {
  int row0 = 0, row1 = 0;
  float c0 = 0, c1 = 0;
};

inline VerticalTaps verticalTaps(int y, int whole, float top, float bottom, int nt) {
  const int upper = y + whole, lower = upper + 1;
  const float c0 = upper >= 0 && upper < nt ? top : 0.0f, c1 = lower >= 0 && lower < nt ? bottom : 0.0f;
  if (c0 == 0.0f) return {lower, lower, c1, 0.0f};
  if (c1 == 0.0f) return {upper, upper, c0, 0.0f};
  return {upper, lower, c0, c1};
}

// One view's channel over output rows [y0, y1): accumulator row (y - y0) (rows of ns floats)
// gains accumulateBilinearRow's taps of `plane` (nt rows of ns floats) at the view's constant
// shift, whole columns wholeX with coefficients ax0, ax1, whole rows wholeY with top and bottom
// as in verticalTaps. One call per block and channel, so that the row loop is inside the SIMD
// code (no dispatch per row), and each row prefetches the source row the next one reads; the last
// row prefetches nextPass (if not null), the first source row of the call that comes next.
void accumulateBilinearRows(float* accumulator, const float* plane, int ns, int nt, int y0, int y1, int wholeX,
                            float ax0, float ax1, int wholeY, float top, float bottom, const float* nextPass);

// out[i] = a[i] * b[i].
void multiplyRows(float* out, const float* a, const float* b, int count);

// out[i] = sum[i] / weight[i], or 0 where weight[i] <= 0 (no ray arrived).
void normaliseRow(float* out, const float* sum, const float* weight, int count);

// Rows [y0, y1) of `out` from a block's accumulators: channel c's row y is accumulatorRow(c, y)
// divided by the weight that arrived, accumulated as one more plane (accumulatorRow(channels, y))
// when `accumulated`, else separable: columnWeight[x] * rowWeight[y].
template <class AccumulatorRow>
void normaliseBlock(Image& out, int y0, int y1, bool accumulated, const AccumulatorRow& accumulatorRow,
                    const std::vector<float>& columnWeight, const std::vector<float>& rowWeight) {
  const int width = out.width(), channels = out.channels();
  std::vector<float> weightRow(accumulated ? 0 : width);
  for (int y = y0; y < y1; ++y) {
    const float* weight = weightRow.data();
    if (accumulated) {
      weight = accumulatorRow(channels, y);
    } else {
      for (int x = 0; x < width; ++x) weightRow[x] = columnWeight[x] * rowWeight[y];
    }
    for (int c = 0; c < channels; ++c) normaliseRow(out.row(y, c), accumulatorRow(c, y), weight, width);
  }
}

}  // namespace lfcam
