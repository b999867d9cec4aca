// The throwaway process that fragile parsers run in first (src/io/survives_in_child.hpp).
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>

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

}  // namespace
}  // namespace lfcam::io
