// The schedule of the shift-and-add kernels (refocus.cpp, tilted_focus.cpp): blocks of output rows
// whose accumulators (about 128 KiB) stay in L2 while every view streams through them; each block
// re-reads one source row per view from memory, so taller blocks waste less bandwidth. At least 8
// blocks, so both cores stay busy to the end. Internal to the library.
#pragma once

#include <algorithm>
#include <cstddef>

#include "core/parallel.hpp"

namespace lfcam {

// Calls renderRows(y0, y1) over [0, rows) in blocks, in parallel; `planes`: the accumulator
// planes of `width` floats per row that a block sums into at once.
template <typename RenderRows>
void forEachRowBlock(int rows, int width, int planes, RenderRows&& renderRows) {
  int blockRows = std::max(1, 32768 / std::max(1, planes * width));
  blockRows = std::clamp(blockRows, 1, std::max(1, (rows + 7) / 8));
  const std::size_t blocks = (std::size_t(rows) + blockRows - 1) / blockRows;
  parallelFor(0, blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t block = begin; block < end; ++block) {
      const int y0 = int(block) * blockRows;
      renderRows(y0, std::min(rows, y0 + blockRows));
    }
  });
}

}  // namespace lfcam
