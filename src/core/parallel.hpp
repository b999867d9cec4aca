// The one place where lfcam decides how work is spread over threads. Kernels are written for a
// range of rows (or items); parallelFor runs them on oneTBB's pool.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>

#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

// Calls body(begin_i, end_i) on disjoint sub-ranges covering [begin, end), possibly in parallel.
// grain: the smallest sub-range worth a task.
void parallelFor(std::size_t begin, std::size_t end, std::size_t grain,
                 const std::function<void(std::size_t, std::size_t)>& body);

// The same in `slices` successive parts, calling progress(fraction done) from the calling thread
// after each: for long loops whose caller shows a progress bar. Without a callback, one part.
void parallelFor(std::size_t begin, std::size_t end, std::size_t grain,
                 const std::function<void(std::size_t, std::size_t)>& body, const ProgressCallback& progress,
                 std::size_t slices = 50);

// Work handed to the same pool to run beside the caller's, so that writing one result overlaps
// computing the next (e.g. the slices of a focal stack). At most `pending` tasks wait at a time:
// beyond that, add() first finishes them all (the caller helps, so one thread suffices), which
// bounds the memory the tasks hold, and returns the first error so far so that the caller can stop.
// wait() (also called by the destructor) finishes every task and returns the first error in the
// order the tasks were added.
class BackgroundTasks {
 public:
  explicit BackgroundTasks(std::size_t pending);
  ~BackgroundTasks();
  BackgroundTasks(const BackgroundTasks&) = delete;
  BackgroundTasks& operator=(const BackgroundTasks&) = delete;

  Status add(std::function<Status()> task);
  Status wait();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Cooperative cancellation, for interactive callers (the Python package on Ctrl-C): while it is
// requested, parallelFor starts no further sub-range, so a long call returns soon. Its result is
// then meaningless: whoever requested the cancellation discards it, then withdraws the request.
void requestCancellation(bool requested);
bool cancellationRequested();

// Limits every later parallelFor to `threads` threads (0: all cores). Lives for the process.
void setThreadCount(int threads);

}  // namespace lfcam
