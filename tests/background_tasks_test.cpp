// BackgroundTasks (parallel.hpp): every task runs, the first error in the order of addition wins,
// add() reports an error once it has had to wait, and one thread suffices (no deadlock).
#include <gtest/gtest.h>

#include <atomic>
#include <string>

#include "core/parallel.hpp"

namespace lfcam {
namespace {

Status failing(const std::string& what) { return makeError(ErrorCode::Io, what); }

TEST(BackgroundTasks, RunsEveryTaskAndReturnsTheFirstErrorInOrder) {
  for (int threads : {1, 0}) {  // 1: the caller runs every task itself
    setThreadCount(threads);
    std::atomic<int> ran = 0;
    BackgroundTasks tasks(3);
    int stoppedAt = -1;
    for (int i = 0; i < 10 && stoppedAt < 0; ++i) {
      const Status added = tasks.add([&ran, i]() -> Status {
        ++ran;
        if (i == 4 || i == 7) return failing("task " + std::to_string(i));
        return {};
      });
      if (!added) {
        EXPECT_EQ(added.error().message, "task 4");
        stoppedAt = i;
      }
    }
    // Three waiting: the 7th addition (i = 6) waits for tasks 3 to 5 and finds task 4's error.
    EXPECT_EQ(stoppedAt, 6);
    const Status all = tasks.wait();
    ASSERT_FALSE(all);
    EXPECT_EQ(all.error().message, "task 4");
    EXPECT_EQ(ran.load(), 6);
  }
  setThreadCount(0);
}

TEST(BackgroundTasks, SucceedsWhenEveryTaskDoes) {
  std::atomic<int> ran = 0;
  {
    BackgroundTasks tasks(2);
    for (int i = 0; i < 20; ++i) ASSERT_TRUE(tasks.add([&ran]() -> Status { return ++ran, Status{}; }));
    EXPECT_TRUE(tasks.wait());
  }
  EXPECT_EQ(ran.load(), 20);
}

}  // namespace
}  // namespace lfcam
