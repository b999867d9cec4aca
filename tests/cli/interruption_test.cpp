// A run killed (SIGKILL) while it writes a large output leaves at the destination either what was
// there before or the complete new output, never a truncated one. The kill moments are fractions of
// a measured uninterrupted run, so the test means the same in fast and sanitized builds.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "cli_support.hpp"
#include "lfcam/io/light_field_io.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Kills the run after `delay` (unless it ended first); true when it was killed.
bool runAndKillAfter(const std::vector<std::string>& args, Clock::duration delay) {
  const pid_t pid = test::startLfcam(args, "/dev/null", "/dev/null");
  std::this_thread::sleep_for(delay);
  const bool killed = kill(pid, SIGKILL) == 0;
  int status = 0;
  waitpid(pid, &status, 0);
  return killed && WIFSIGNALED(status);
}

Clock::duration timeOf(const std::vector<std::string>& args, const fs::path& scratch) {
  const auto start = Clock::now();
  const auto result = test::runLfcam(args, scratch);
  EXPECT_EQ(result.exitStatus, 0) << result.err;
  return Clock::now() - start;
}

class Interruption : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    // 9 x 9 views of 160 x 160 RGB: 25 MB of samples, about a second to write.
    const auto made = test::runLfcam({"synth", "--views", "9", "--size", "160", "-o", source().string()}, dir_->path());
    ASSERT_EQ(made.exitStatus, 0) << made.err;
    auto read = readLightField(source());
    ASSERT_TRUE(read.ok()) << read.error().message;
    samples_ = new std::vector<float>(read->samples().begin(), read->samples().end());
  }
  static void TearDownTestSuite() {
    delete samples_;
    delete dir_;
  }
  static fs::path source() { return dir_->path() / "big.lf.h5"; }
  static const std::vector<float>& samples() { return *samples_; }

 private:
  static test::TempDir* dir_;
  static std::vector<float>* samples_;
};
test::TempDir* Interruption::dir_ = nullptr;
std::vector<float>* Interruption::samples_ = nullptr;

TEST_F(Interruption, KilledHdf5WriteLeavesOldFileOrComplete) {
  test::TempDir dir;
  const fs::path out = dir / "out.lf.h5";
  const std::vector<std::string> convert = {"convert", source().string(), "-o", out.string()};
  const auto full = timeOf(convert, dir.path());
  fs::remove(out);
  // A small old file at the destination for half of the runs.
  const fs::path old = dir / "old.lf.h5";
  ASSERT_EQ(test::runLfcam({"synth", "--views", "2", "--size", "8", "-o", old.string()}, dir.path()).exitStatus, 0);
  const std::string oldBytes = test::readBytes(old);

  int killed = 0;
  for (double fraction : {0.05, 0.2, 0.4, 0.6, 0.8, 0.95}) {
    for (bool withOld : {false, true}) {
      SCOPED_TRACE(testing::Message() << "killed at " << fraction << " of the run, old file: " << withOld);
      fs::remove(out);
      if (withOld) fs::copy_file(old, out);
      killed += runAndKillAfter(convert, std::chrono::duration_cast<Clock::duration>(full * fraction));
      if (!fs::exists(out)) {
        EXPECT_FALSE(withOld) << "the old file disappeared";
        continue;
      }
      const std::string bytes = test::readBytes(out);
      if (withOld && bytes == oldBytes) continue;
      auto read = readLightField(out);
      ASSERT_TRUE(read.ok()) << "a damaged output: " << read.error().message;
      EXPECT_TRUE(std::equal(read->samples().begin(), read->samples().end(), samples().begin(), samples().end()));
    }
  }
  // Most moments fall inside the run; if none did the test proved nothing.
  EXPECT_GE(killed, 6);
}

TEST_F(Interruption, KilledFolderWriteLeavesNoFolderOrComplete) {
  test::TempDir dir;
  const fs::path out = dir / "views";
  const std::vector<std::string> convert = {"convert", source().string(), "-o", out.string()};
  const auto full = timeOf(convert, dir.path());
  int killed = 0;
  for (double fraction : {0.1, 0.4, 0.7, 0.9}) {
    SCOPED_TRACE(testing::Message() << "killed at " << fraction << " of the run");
    fs::remove_all(out);
    killed += runAndKillAfter(convert, std::chrono::duration_cast<Clock::duration>(full * fraction));
    if (!fs::exists(out)) continue;  // the new folder appears whole, by one rename, or not at all
    auto read = readLightField(out);
    ASSERT_TRUE(read.ok()) << "a damaged output: " << read.error().message;
    EXPECT_EQ(read->shape().views(), 81u);
  }
  EXPECT_GE(killed, 2);
}

}  // namespace
}  // namespace lfcam
