// The one place where lfcam decides how work is spread over threads. Kernels are written for a
// range of rows (or items); parallelFor runs them on oneTBB's pool.
#pragma once

#include <cstddef>
#include <functional>

namespace lfcam {

// Calls body(begin_i, end_i) on disjoint sub-ranges covering [begin, end), possibly in parallel.
// grain: the smallest sub-range worth a task.
void parallelFor(std::size_t begin, std::size_t end, std::size_t grain,
                 const std::function<void(std::size_t, std::size_t)>& body);

// Limits every later parallelFor to `threads` threads (0: all cores). Lives for the process.
void setThreadCount(int threads);

}  // namespace lfcam
