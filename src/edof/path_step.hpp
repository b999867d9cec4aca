// One step of a semi-global path (semiGlobalMatching, semi_global.cpp): from prev = Lr(p - r, .),
//   cur[l] = cost[l] + min(prev[l], min(prev[l - 1], prev[l + 1]) + p1, min_k prev[k] + p2) - min_k prev[k]
// (the neighbours that exist), and sum[l] += cur[l], over `labels` >= 1. The fast kernel is SIMD
// across the labels through Highway with run-time dispatch and gives the same bits as the scalar
// reference: additions and minima only, each label's in the same order.
#pragma once

#include <algorithm>

namespace lfcam::edof {

void pathStep(const float* cost, const float* prev, float* cur, float* sum, int labels, float p1, float p2);
// One label at a time: the reference the fast kernel is tested against, and the path for fewer
// labels than a vector and two.
void pathStepReference(const float* cost, const float* prev, float* cur, float* sum, int labels, float p1, float p2);

// Label l of a step whose prev has the least value minPrev, jump = minPrev + p2 (labels >= 2): both
// kernels' formula.
inline float pathStepLabel(const float* cost, const float* prev, int l, int labels, float p1, float jump,
                           float minPrev) {
  const float neighbour = l == 0 ? prev[1] : l + 1 == labels ? prev[l - 1] : std::min(prev[l - 1], prev[l + 1]);
  return cost[l] + std::min(std::min(prev[l], neighbour + p1), jump) - minPrev;
}

}  // namespace lfcam::edof
