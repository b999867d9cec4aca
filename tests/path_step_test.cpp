// The semi-global path step's SIMD kernel (src/edof/path_step.hpp) against its scalar reference,
// bit for bit, on every instruction set this CPU runs (Highway's dispatch forced to each in turn):
// random costs and previous steps, label counts from 1 to past several vectors with tails, penalties
// that make every branch of the minimum win somewhere.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include <hwy/targets.h>

#include "edof/path_step.hpp"

namespace lfcam::edof {
namespace {

TEST(PathStep, EverySimdTargetMatchesTheScalarReferenceBitForBit) {
  std::mt19937 random(51);
  std::uniform_real_distribution<float> value(0, 1), penalty(0, 0.5f);
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (std::int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    for (int labels = 1; labels <= 100; ++labels)
      for (int trial = 0; trial < 4; ++trial) {
        std::vector<float> cost(labels), prev(labels), sum(labels), cur(labels), curReference(labels);
        for (int l = 0; l < labels; ++l) cost[l] = value(random), prev[l] = value(random), sum[l] = value(random);
        std::vector<float> sumReference(sum);
        const float p1 = 0.1f * penalty(random), p2 = penalty(random);
        pathStep(cost.data(), prev.data(), cur.data(), sum.data(), labels, p1, p2);
        pathStepReference(cost.data(), prev.data(), curReference.data(), sumReference.data(), labels, p1, p2);
        ASSERT_EQ(cur, curReference) << "target " << hwy::TargetName(target) << ", " << labels << " labels";
        ASSERT_EQ(sum, sumReference) << "target " << hwy::TargetName(target) << ", " << labels << " labels";
      }
  }
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace
}  // namespace lfcam::edof
