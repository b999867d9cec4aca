// Semi-global optimisation of a cost volume and the winner-takes-all read-out (edof_internal.hpp).
#include <algorithm>
#include <cmath>

#include "core/parabola.hpp"
#include "core/parallel.hpp"
#include "edof/edof_internal.hpp"

namespace lfcam::edof {

namespace {

// Schedule: the label loop vectorises (LFCAM_CLONES).
// One step of a path: cur = Lr(p, .) from prev = Lr(p - r, .); sum += cur.
LFCAM_CLONES void pathStep(const float* __restrict cost, const float* __restrict prev, float* __restrict cur,
                           float* __restrict sum, int labels, float p1, float p2) {
  float minPrev = prev[0];
  for (int l = 1; l < labels; ++l) minPrev = std::min(minPrev, prev[l]);
  const float jump = minPrev + p2;
  if (labels == 1) {
    cur[0] = cost[0];
    sum[0] += cur[0];
    return;
  }
  cur[0] = cost[0] + std::min(std::min(prev[0], prev[1] + p1), jump) - minPrev;
  for (int l = 1; l < labels - 1; ++l) {
    const float neighbour = std::min(prev[l - 1], prev[l + 1]) + p1;
    cur[l] = cost[l] + std::min(std::min(prev[l], neighbour), jump) - minPrev;
  }
  cur[labels - 1] = cost[labels - 1] + std::min(std::min(prev[labels - 1], prev[labels - 2] + p1), jump) - minPrev;
  for (int l = 0; l < labels; ++l) sum[l] += cur[l];
}

LFCAM_CLONES void startPath(const float* __restrict cost, float* __restrict cur, float* __restrict sum, int labels) {
  for (int l = 0; l < labels; ++l) {
    cur[l] = cost[l];
    sum[l] += cost[l];
  }
}

}  // namespace

CostVolume semiGlobalMatching(const CostVolume& cost, int width, int height, int labels, const float* guide, float p1,
                              float p2, float edgeScale) {
  const std::size_t L = std::size_t(labels);
  CostVolume sum(cost.size());
  auto jumpPenalty = [&](std::size_t p, std::size_t q) {
    const float step = std::abs(guide[p] - guide[q]);
    return std::max(p1, p2 / (1.0f + step / edgeScale));
  };

  const int directions[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
  for (const auto& direction : directions) {
    const int dx = direction[0], dy = direction[1];
    if (dy == 0) {
      // Along rows: rows are independent.
      parallelFor(0, std::size_t(height), 8, [&](std::size_t begin, std::size_t end) {
        std::vector<float> a(L), b(L);
        for (std::size_t y = begin; y < end; ++y) {
          float *prev = a.data(), *cur = b.data();
          for (int i = 0; i < width; ++i) {
            const int x = dx > 0 ? i : width - 1 - i;
            const std::size_t p = y * width + x;
            if (i == 0) {
              startPath(&cost[p * L], cur, &sum[p * L], labels);
            } else {
              const std::size_t q = y * width + (x - dx);
              pathStep(&cost[p * L], prev, cur, &sum[p * L], labels, p1, jumpPenalty(p, q));
            }
            std::swap(prev, cur);
          }
        }
      });
      continue;
    }
    // Across rows: one row after another, the pixels of a row in parallel.
    std::vector<float> previousRow(std::size_t(width) * L), currentRow(std::size_t(width) * L);
    for (int i = 0; i < height; ++i) {
      const int y = dy > 0 ? i : height - 1 - i;
      parallelFor(0, std::size_t(width), 64, [&](std::size_t begin, std::size_t end) {
        for (std::size_t x = begin; x < end; ++x) {
          const std::size_t p = std::size_t(y) * width + x;
          const long px = long(x) - dx;
          float* cur = &currentRow[x * L];
          if (i == 0 || px < 0 || px >= width) {
            startPath(&cost[p * L], cur, &sum[p * L], labels);
          } else {
            const std::size_t q = std::size_t(y - dy) * width + std::size_t(px);
            pathStep(&cost[p * L], &previousRow[std::size_t(px) * L], cur, &sum[p * L], labels, p1, jumpPenalty(p, q));
          }
        }
      });
      std::swap(previousRow, currentRow);
    }
  }
  return sum;
}

void winnerTakesAll(const CostVolume& volume, int width, int height, int labels, float* label) {
  const std::size_t L = std::size_t(labels);
  parallelFor(0, std::size_t(width) * height, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      const float* c = &volume[p * L];
      const int best = int(std::min_element(c, c + L) - c);
      double offset = 0;
      if (best > 0 && best + 1 < labels) {
        offset = parabolaVertex(c[best - 1], c[best], c[best + 1]);
      }
      label[p] = float(best + offset);
    }
  });
}

}  // namespace lfcam::edof
