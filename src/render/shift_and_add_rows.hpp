// The row kernels of the fast shift-and-add (refocus.cpp), in SIMD through Highway with run-time
// dispatch: each call runs the widest instruction set the CPU has (AVX-512, AVX2, SSE4, ...).
// Internal to the library.
#pragma once

#include <vector>

#include "lfcam/core/image.hpp"

namespace lfcam {

// One source row of one view, sampled at a constant horizontal shift: output column x takes
// c0 row[x + whole] + c1 row[x + whole + 1], a tap whose column lies outside [0, ns) counting as
// 0 (the view ends there).
struct ShiftedRow {
  const float* row = nullptr;
  int whole = 0;
  float c0 = 0, c1 = 0;
};

// An output row that gains the vertical taps of two horizontal sums (refocus.cpp):
// accumulator[x] += top * above[x] + bottom * (the sum being made)[x].
struct OutputRow {
  float* accumulator = nullptr;
  const float* above = nullptr;
  float top = 0, bottom = 0;
};

// sum[x] = the taps of every row in rows[0, count) at output column x, for x in [0, ns) (0 for
// none), then, when `out` is not null, out's row finished from it. Rows are summed a few at a
// time (up to 9, sum loaded and stored once for them all), each at its own shift: one SIMD loop
// over the columns where all of them have both taps inside, the few columns on either side row by
// row. A single pass stores sum and finishes out in the same loop.
void sumShiftedRows(float* sum, const ShiftedRow* rows, int count, int ns, const OutputRow* out);

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
