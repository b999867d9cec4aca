// Animations: MP4 videos decode back to the frames written (count and size, odd sizes grown to
// even), failures leave no file, and the format follows the extension.
#include "lfcam/animation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <vector>

#include "test_support.hpp"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

// `count` frames of a bright square moving across a dark background.
std::vector<Image> movingSquare(int count, int width, int height, int channels) {
  std::vector<Image> frames;
  for (int f = 0; f < count; ++f) {
    Image frame(width, height, channels);
    for (int c = 0; c < channels; ++c)
      for (int y = height / 4; y < height / 2; ++y)
        for (int x = f; x < std::min(width, f + width / 4); ++x) frame.at(x, y, c) = 0.8f;
    frames.push_back(std::move(frame));
  }
  return frames;
}

TEST(Animation, Mp4DecodesBackToItsFrames) {
  test::TempDir dir;
  const fs::path path = dir / "clip.mp4";
  ASSERT_TRUE(writeAnimation(path, movingSquare(7, 64, 48, 3), 12));
  auto summary = readVideoSummary(path);
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(summary->frames, 7);
  EXPECT_EQ(summary->width, 64);
  EXPECT_EQ(summary->height, 48);
  EXPECT_TRUE(summary->codec == "h264" || summary->codec == "mpeg4") << summary->codec;
  // Nothing else in the folder: the temporary name was renamed, not left beside it.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(Animation, Mp4OfOddSizeAndGreyFramesGrowsToEvenSize) {
  test::TempDir dir;
  ASSERT_TRUE(writeMp4Video(dir / "odd.mp4", movingSquare(3, 41, 29, 1), 5));
  auto summary = readVideoSummary(dir / "odd.mp4");
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(summary->frames, 3);
  EXPECT_EQ(summary->width, 42);
  EXPECT_EQ(summary->height, 30);
}

TEST(Animation, FailuresLeaveNoFile) {
  test::TempDir dir;
  const auto frames = movingSquare(2, 16, 16, 3);
  // A folder that does not exist: failed work, nothing written anywhere.
  const Status missing = writeAnimation(dir / "none" / "clip.mp4", frames, 10);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().code, ErrorCode::Usage);
  EXPECT_FALSE(fs::exists(dir / "none"));
  // Usage errors: another extension, no frames, mixed sizes, a bad rate.
  for (const Status& status :
       {writeAnimation(dir / "clip.avi", frames, 10), writeAnimation(dir / "clip.mp4", {}, 10),
        writeAnimation(dir / "clip.mp4", movingSquare(1, 8, 8, 3), 0)}) {
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().code, ErrorCode::Usage) << status.error().message;
  }
  std::vector<Image> mixed = movingSquare(1, 16, 16, 3);
  mixed.push_back(Image(8, 8, 3));
  EXPECT_FALSE(writeAnimation(dir / "clip.mp4", mixed, 10));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 0);
  // A file that is no video.
  EXPECT_FALSE(readVideoSummary(dir / "absent.mp4"));
}

}  // namespace
}  // namespace lfcam
