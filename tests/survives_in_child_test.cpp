// The throwaway process that fragile parsers run in first (src/io/survives_in_child.hpp).
#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <memory>
#include <thread>
#include <vector>

#include <unistd.h>

#include "io/survives_in_child.hpp"

namespace lfcam::io {
namespace {

using namespace std::chrono_literals;

TEST(SurvivesInChild, OutcomeOfEachEnding) {
  int touched = 0;
  EXPECT_EQ(survivesInChild([&] { touched = 1; }, 10s), ChildOutcome::Survived);
  EXPECT_EQ(touched, 0);  // the work ran in another process
  EXPECT_EQ(survivesInChild([] { std::raise(SIGSEGV); }, 10s), ChildOutcome::Crashed);
  EXPECT_EQ(survivesInChild([] { std::abort(); }, 10s), ChildOutcome::Crashed);
  EXPECT_EQ(survivesInChild([] { std::_Exit(1); }, 10s), ChildOutcome::Crashed);  // a sanitizer's exit
  EXPECT_EQ(survivesInChild(
                [] {
                  for (;;) pause();
                },
                200ms),
            ChildOutcome::TimedOut);
}

// A child forked while another thread is inside the allocator must still be able to allocate (under
// clang 14's AddressSanitizer it waited for ever: `lfcam batch --jobs 2` reported good files as hangs).
TEST(SurvivesInChild, ChildAllocatesWhileAnotherThreadDoes) {
  std::atomic<bool> stop = false;
  std::thread allocating([&] {
    std::vector<std::unique_ptr<char[]>> blocks;
    while (!stop) {
      for (int i = 0; i < 512; ++i) blocks.emplace_back(new char[16 + 48 * (i % 64)]);
      blocks.clear();  // keeps the allocator refilling and draining its caches, under its locks
    }
  });
  int outcomes[3] = {};
  for (int i = 0; i < 200; ++i) {
    const ChildOutcome outcome = survivesInChild(
        [] {
          std::vector<std::unique_ptr<char[]>> blocks;
          for (int size = 16; size < (1 << 20); size = size * 5 / 4 + 16) blocks.emplace_back(new char[size]);
        },
        10s);
    ++outcomes[int(outcome)];
  }
  stop = true;
  allocating.join();
  EXPECT_EQ(outcomes[int(ChildOutcome::Crashed)], 0);
  // Under clang 14's ASan the quarantine's lock stays out of reach (survives_in_child.hpp): a child
  // forked while the other thread holds it times out (seen: 1 of 200 in about one run in six, gdb
  // showing the child in Quarantine::Drain). Everywhere else every child must survive.
  const int allowedTimeouts = childMayWaitOnALockHeldAtFork() ? 5 : 0;
  EXPECT_LE(outcomes[int(ChildOutcome::TimedOut)], allowedTimeouts)
      << outcomes[int(ChildOutcome::Survived)] << " of 200 survived";
}

}  // namespace
}  // namespace lfcam::io
