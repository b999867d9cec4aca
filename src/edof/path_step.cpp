// The semi-global path step of path_step.hpp in Highway, float lanes across the labels.
// foreach_target.h compiles this file once per instruction set; HWY_DYNAMIC_DISPATCH picks one on
// the first call.
#include "edof/path_step.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "edof/path_step.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace lfcam::edof {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

void PathStep(const float* HWY_RESTRICT cost, const float* HWY_RESTRICT prev, float* HWY_RESTRICT cur,
              float* HWY_RESTRICT sum, int labels, float p1, float p2) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  if (labels < lanes + 2) return pathStepReference(cost, prev, cur, sum, labels, p1, p2);
  auto least = hn::LoadU(d, prev);
  int l = lanes;
  for (; l + lanes <= labels; l += lanes) least = hn::Min(least, hn::LoadU(d, prev + l));
  float minPrev = hn::GetLane(hn::MinOfLanes(d, least));
  for (; l < labels; ++l) minPrev = std::min(minPrev, prev[l]);
  const float jump = minPrev + p2;
  const auto step = [&](int label) {
    cur[label] = pathStepLabel(cost, prev, label, labels, p1, jump, minPrev);
    sum[label] += cur[label];
  };
  step(0);
  const auto penalty = hn::Set(d, p1), jumpTo = hn::Set(d, jump), floor = hn::Set(d, minPrev);
  // Labels [1, labels - 1) have both neighbours: whole vectors of them, then one at a time.
  for (l = 1; l + lanes < labels; l += lanes) {
    const auto neighbour = hn::Add(hn::Min(hn::LoadU(d, prev + l - 1), hn::LoadU(d, prev + l + 1)), penalty);
    const auto value =
        hn::Sub(hn::Add(hn::LoadU(d, cost + l), hn::Min(hn::Min(hn::LoadU(d, prev + l), neighbour), jumpTo)), floor);
    hn::StoreU(value, d, cur + l);
    hn::StoreU(hn::Add(hn::LoadU(d, sum + l), value), d, sum + l);
  }
  for (; l < labels; ++l) step(l);
}

}  // namespace HWY_NAMESPACE
}  // namespace lfcam::edof
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam::edof {

HWY_EXPORT(PathStep);

void pathStep(const float* cost, const float* prev, float* cur, float* sum, int labels, float p1, float p2) {
  HWY_DYNAMIC_DISPATCH(PathStep)(cost, prev, cur, sum, labels, p1, p2);
}

void pathStepReference(const float* cost, const float* prev, float* cur, float* sum, int labels, float p1, float p2) {
  if (labels == 1) {
    cur[0] = cost[0];
    sum[0] += cur[0];
    return;
  }
  float minPrev = prev[0];
  for (int l = 1; l < labels; ++l) minPrev = std::min(minPrev, prev[l]);
  const float jump = minPrev + p2;
  for (int l = 0; l < labels; ++l) {
    cur[l] = pathStepLabel(cost, prev, l, labels, p1, jump, minPrev);
    sum[l] += cur[l];
  }
}

}  // namespace lfcam::edof
#endif  // HWY_ONCE
