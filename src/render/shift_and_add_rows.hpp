// The row kernels of the fast shift-and-add (refocus.cpp), in SIMD through Highway with run-time
// dispatch: each call runs the widest instruction set the CPU has (AVX-512, AVX2, SSE4, ...).
// Internal to the library.
#pragma once

namespace lfcam {

// One view's contribution to one output row, at a constant shift: for every output column x in
// [0, ns), with source column s = x + whole,
//   accumulator[x] += c00 row0[s] + c01 row0[s + 1] + c10 row1[s] + c11 row1[s + 1]
// where a tap whose column lies outside [0, ns) counts as 0 (the view ends there). row0 and row1
// are the two source rows of the vertical taps (they may be the same row when c10 = c11 = 0).
// nextRow, when not null, is the source row the next call will read: it is prefetched.
void accumulateBilinearRow(float* accumulator, const float* row0, const float* row1, int whole, float c00, float c01,
                           float c10, float c11, int ns, const float* nextRow = nullptr);

// out[i] = a[i] * b[i].
void multiplyRows(float* out, const float* a, const float* b, int count);

// out[i] = sum[i] / weight[i], or 0 where weight[i] <= 0 (no ray arrived).
void normaliseRow(float* out, const float* sum, const float* weight, int count);

}  // namespace lfcam
