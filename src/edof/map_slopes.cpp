// The map's local slope (edof_internal.hpp), for the cleanup steps that carry disparities from
// neighbours: the slanted weighted median and the occlusion edges.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/box_filter.hpp"
#include "core/parallel.hpp"
#include "edof/edof_internal.hpp"

namespace lfcam::edof {

namespace {

// The map's local slope: central differences of its box mean over
// (2 kSlopeRadius + 1)^2 pixels, measured where no jump of more than kSlopeJump px between
// 4-neighbours lies within kSlopeRadius + 1 pixels (there the mean mixes two surfaces). Beside a
// jump (and in the image's outermost pixels) a pixel takes the mean slope measured within
// kSlopeReach pixels on its own surface (disparity within kSlopeJump per pixel of distance, plus
// one): else the median is flat there, and at the far end of a slanted floor, or on the side of a
// column turning away, its window holds only the surface's inner part and takes its disparity
// (steep slants 2.65 % flat beside jumps, 1.13 % with the reach below). Slopes under
// kSlopeMin px per pixel along both axes count as none (on a plane facing the camera the slope of
// the map's noise only roughens it).
// Chosen on the development scenes, one setting after the other, by the mean BadPix(0.07) at 128
// and 256 px per view and the mean bumpiness at 128 (a plain median: 2.45 %, 3.56 %, 0.951):
//   jump 0.1, 0.15, 0.2 px (radius 2, no minimum, flat beside jumps): 2.41 and 3.55 %; 2.31 and
//     3.65; 2.43 at 128. Without the jump test every occlusion edge got a slope: 9.42 %;
//   radius 1 and 3 (jump 0.15): 2.34 and 2.34 % at 128;
//   minimum 0, 0.005, 0.01, 0.02 (jump 0.1): 2.41, 2.39, 2.38, 2.39 % and bumpiness 0.975, 0.953,
//     0.932, 0.921; at 256 px 3.54 % for 0.01, 3.56 % for 0.02;
//   reach 0 (flat beside jumps), 4, 5, 7, 9: 2.38, 2.18, 1.97, 1.93, 2.03 % at 128; 3.54, 3.51 and
//     3.50 % at 256 for 0, 5 and 7; bumpiness 0.932 and 0.841 for 0 and 7;
//   then minimum 0.005 (reach 7): 1.88 and 3.52 %, bumpiness 0.886.
constexpr int kSlopeRadius = 2;
constexpr float kSlopeJump = 0.1f;
constexpr float kSlopeMin = 0.01f;
constexpr int kSlopeReach = 7;

}  // namespace

MapSlopes mapSlopes(const float* disparity, int width, int height) {
  const std::size_t n = std::size_t(width) * height;
  MapSlopes measured{std::vector<float>(n, 0.0f), std::vector<float>(n, 0.0f)};
  std::vector<char> isMeasured(n, 0);
  std::vector<float> mean(n);
  boxFilter(disparity, mean.data(), width, height, kSlopeRadius);
  const std::vector<int> jumps = jumpDistance(disparity, width, height, kSlopeJump, kSlopeRadius + 1);
  for (int y = 1; y + 1 < height; ++y)
    for (int x = 1; x + 1 < width; ++x) {
      const std::size_t p = std::size_t(y) * width + x;
      if (jumps[p] <= kSlopeRadius + 1) continue;
      measured.x[p] = 0.5f * (mean[p + 1] - mean[p - 1]);
      measured.y[p] = 0.5f * (mean[p + width] - mean[p - width]);
      isMeasured[p] = 1;
    }
  MapSlopes slopes = measured;
  parallelFor(0, std::size_t(height), 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t p = y * width + x;
        if (!isMeasured[p]) {
          double sumX = 0, sumY = 0;
          int count = 0;
          for (int qy = std::max(int(y) - kSlopeReach, 0); qy <= std::min(int(y) + kSlopeReach, height - 1); ++qy)
            for (int qx = std::max(x - kSlopeReach, 0); qx <= std::min(x + kSlopeReach, width - 1); ++qx) {
              const std::size_t q = std::size_t(qy) * width + qx;
              const int distance = std::max(std::abs(qx - x), std::abs(qy - int(y)));
              if (isMeasured[q] && std::abs(disparity[q] - disparity[p]) <= kSlopeJump * float(distance + 1))
                sumX += measured.x[q], sumY += measured.y[q], ++count;
            }
          if (count > 0) slopes.x[p] = float(sumX / count), slopes.y[p] = float(sumY / count);
        }
        if (std::max(std::abs(slopes.x[p]), std::abs(slopes.y[p])) < kSlopeMin) slopes.x[p] = slopes.y[p] = 0;
      }
  });
  return slopes;
}

}  // namespace lfcam::edof
