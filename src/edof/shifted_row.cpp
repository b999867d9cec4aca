// The fast row sampler of depth's cost volume (edof_internal.hpp), tested against
// bilinearSample (core/bilinear.hpp) on random planes and shifts.
#include <algorithm>
#include <cmath>

#include "edof/edof_internal.hpp"

namespace lfcam::edof {

namespace {

// The clones stay in this file: a declaration with target_clones elsewhere would make every
// includer emit its own resolver.
LFCAM_CLONES void shiftedRow(const float* __restrict plane, int ns, int nt, int y, double shiftX, double shiftY,
                             int pad, float* __restrict padded, float* __restrict out) {
  const double rowPosition = y + shiftY;
  const double rowFloor = std::floor(rowPosition);
  const float fy = float(rowPosition - rowFloor);
  const int r0 = std::clamp(int(rowFloor), 0, nt - 1), r1 = std::clamp(int(rowFloor) + 1, 0, nt - 1);
  const float* row0 = plane + std::size_t(r0) * ns;
  const float* row1 = plane + std::size_t(r1) * ns;
  float* body = padded + pad;
  for (int x = 0; x < ns; ++x) body[x] = row0[x] + fy * (row1[x] - row0[x]);
  for (int i = 1; i <= pad; ++i) {
    body[-i] = body[0];
    body[ns - 1 + i] = body[ns - 1];
  }
  const double limit = pad - 2;
  const double shift = std::clamp(shiftX, -limit, limit);
  const double shiftFloor = std::floor(shift);
  const float fx = float(shift - shiftFloor);
  const float* source = body + int(shiftFloor);
  for (int x = 0; x < ns; ++x) out[x] = source[x] + fx * (source[x + 1] - source[x]);
}

}  // namespace

void sampleShiftedRow(const float* plane, int ns, int nt, int y, double shiftX, double shiftY, int pad, float* padded,
                      float* out) {
  shiftedRow(plane, ns, nt, y, shiftX, shiftY, pad, padded, out);
}

}  // namespace lfcam::edof
