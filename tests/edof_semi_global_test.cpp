// Semi-global optimisation (src/edof/semi_global.cpp: two sweeps along rows, two across them with
// three paths each) against the recursion of edof_internal.hpp evaluated path by path, pixel by
// pixel, in double, on random volumes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "edof/edof_internal.hpp"

namespace lfcam::edof {
namespace {

// Sum over the 8 paths of Lr(p, l), each path's pixels in the order it runs.
std::vector<double> plainSemiGlobal(const CostVolume& cost, int width, int height, int labels, const float* guide,
                                    double p1, double p2, double edgeScale) {
  const std::size_t L = std::size_t(labels);
  std::vector<double> sum(cost.size(), 0.0);
  const int directions[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
  for (const auto& r : directions) {
    std::vector<double> path(cost.size());
    // Rows (and columns) in the order the path reaches them.
    for (int i = 0; i < height; ++i)
      for (int j = 0; j < width; ++j) {
        const int y = r[1] >= 0 ? i : height - 1 - i, x = r[0] >= 0 ? j : width - 1 - j;
        const std::size_t p = std::size_t(y) * width + x;
        const int qx = x - r[0], qy = y - r[1];
        if (qx < 0 || qx >= width || qy < 0 || qy >= height) {
          for (std::size_t l = 0; l < L; ++l) path[p * L + l] = cost[p * L + l];
        } else {
          const std::size_t q = std::size_t(qy) * width + qx;
          const double* prev = &path[q * L];
          const double lowest = *std::min_element(prev, prev + L);
          const double jump = std::max(p1, p2 / (1 + std::abs(double(guide[p]) - guide[q]) / edgeScale));
          for (std::size_t l = 0; l < L; ++l) {
            double best = std::min(prev[l], lowest + jump);
            if (l > 0) best = std::min(best, prev[l - 1] + p1);
            if (l + 1 < L) best = std::min(best, prev[l + 1] + p1);
            path[p * L + l] = cost[p * L + l] + best - lowest;
          }
        }
      }
    for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += path[k];
  }
  return sum;
}

TEST(SemiGlobalMatching, MatchesThePathRecursionOnRandomVolumes) {
  std::mt19937 generator(51);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int trial = 0; trial < 20; ++trial) {
    // Sizes from a single pixel, labels from 1 (no neighbours) up.
    const int width = 1 + int(generator() % 30), height = 1 + int(generator() % 30), labels = 1 + int(generator() % 40);
    const std::size_t n = std::size_t(width) * height;
    CostVolume cost(n * labels);
    std::vector<float> guide(n);
    for (float& c : cost) c = uniform(generator);
    for (float& g : guide) g = uniform(generator);
    const float p1 = 0.05f, p2 = 0.5f, edgeScale = 0.1f;
    const CostVolume fast = semiGlobalMatching(cost, width, height, labels, guide.data(), p1, p2, edgeScale);
    const std::vector<double> plain = plainSemiGlobal(cost, width, height, labels, guide.data(), p1, p2, edgeScale);
    ASSERT_EQ(fast.size(), plain.size());
    for (std::size_t k = 0; k < plain.size(); ++k)
      ASSERT_NEAR(fast[k], plain[k], 1e-4 * (1 + std::abs(plain[k]))) << "trial " << trial << " entry " << k;
  }
}

}  // namespace
}  // namespace lfcam::edof
