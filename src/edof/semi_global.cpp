// Semi-global optimisation of a cost volume and the winner-takes-all read-out (edof_internal.hpp).
#include <algorithm>
#include <cmath>

#include "core/parabola.hpp"
#include "core/parallel.hpp"
#include "edof/edof_internal.hpp"
#include "edof/path_step.hpp"

namespace lfcam::edof {

namespace {

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

  // Along rows: rows are independent.
  for (const int dx : {1, -1})
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
  // Across rows, down then up: one row after another, the pixels of a row in parallel, the three
  // paths that arrive from the row before (straight, from the left, from the right) in one sweep,
  // so that the volume is read once per sweep rather than once per path (the optimisation is
  // bound by memory).
  constexpr int kAcross[3] = {0, 1, -1};
  const std::size_t rowFloats = std::size_t(width) * L;
  for (const int dy : {1, -1}) {
    std::vector<float> previousRows(3 * rowFloats), currentRows(3 * rowFloats);
    for (int i = 0; i < height; ++i) {
      const int y = dy > 0 ? i : height - 1 - i;
      parallelFor(0, std::size_t(width), 64, [&](std::size_t begin, std::size_t end) {
        for (std::size_t x = begin; x < end; ++x) {
          const std::size_t p = std::size_t(y) * width + x;
          for (int path = 0; path < 3; ++path) {
            const long px = long(x) - kAcross[path];
            float* cur = &currentRows[path * rowFloats + x * L];
            if (i == 0 || px < 0 || px >= width) {
              startPath(&cost[p * L], cur, &sum[p * L], labels);
            } else {
              const std::size_t q = std::size_t(y - dy) * width + std::size_t(px);
              pathStep(&cost[p * L], &previousRows[path * rowFloats + std::size_t(px) * L], cur, &sum[p * L], labels,
                       p1, jumpPenalty(p, q));
            }
          }
        }
      });
      std::swap(previousRows, currentRows);
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
