#include "core/parallel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <deque>
#include <memory>

namespace lfcam {

namespace {
std::unique_ptr<tbb::global_control>& threadLimit() {
  static std::unique_ptr<tbb::global_control> limit;
  return limit;
}
std::atomic<bool> cancelled{false};
}  // namespace

void requestCancellation(bool requested) { cancelled.store(requested, std::memory_order_relaxed); }
bool cancellationRequested() { return cancelled.load(std::memory_order_relaxed); }

void parallelFor(std::size_t begin, std::size_t end, std::size_t grain,
                 const std::function<void(std::size_t, std::size_t)>& body) {
  if (begin >= end) return;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, grain == 0 ? 1 : grain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      if (!cancellationRequested()) body(range.begin(), range.end());
                    });
}

void parallelFor(std::size_t begin, std::size_t end, std::size_t grain,
                 const std::function<void(std::size_t, std::size_t)>& body, const ProgressCallback& progress,
                 std::size_t slices) {
  if (!progress || begin >= end) return parallelFor(begin, end, grain, body);
  const std::size_t total = end - begin;
  slices = std::max<std::size_t>(1, std::min(slices, total));
  for (std::size_t slice = 0; slice < slices; ++slice) {
    parallelFor(begin + total * slice / slices, begin + total * (slice + 1) / slices, grain, body);
    progress(double(slice + 1) / double(slices));
  }
}

struct BackgroundTasks::State {
  std::size_t pending;
  tbb::task_group group;
  std::deque<Status> results;  // one per task since the last wait, in order; stable addresses
  Status firstError;
};

BackgroundTasks::BackgroundTasks(std::size_t pending) : state_(std::make_unique<State>()) {
  state_->pending = std::max<std::size_t>(1, pending);
}

BackgroundTasks::~BackgroundTasks() { (void)wait(); }

Status BackgroundTasks::add(std::function<Status()> task) {
  if (state_->results.size() >= state_->pending) LFCAM_TRY(wait());
  Status& result = state_->results.emplace_back();
  state_->group.run([&result, task = std::move(task)] { result = task(); });
  return {};
}

Status BackgroundTasks::wait() {
  state_->group.wait();
  for (Status& result : state_->results)
    if (!result && state_->firstError) state_->firstError = std::move(result);
  state_->results.clear();
  return state_->firstError;
}

void setThreadCount(int threads) {
  if (threads <= 0) {
    threadLimit().reset();
    return;
  }
  threadLimit() =
      std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
}

}  // namespace lfcam
