// Animations: MP4 videos decode back to the frames written (count and size, odd sizes grown to
// even), failures leave no file, and the format follows the extension.
#include "lfcam/render/animation.hpp"

#include <gif_lib.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <memory>
#include <vector>

#include "lfcam/io/image_io.hpp"
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

// A GIF decoded whole by giflib; null, with the failure recorded, when it cannot be.
struct GifCloser {
  void operator()(GifFileType* gif) const { DGifCloseFile(gif, nullptr); }
};
using DecodedGif = std::unique_ptr<GifFileType, GifCloser>;

DecodedGif slurpGif(const fs::path& path) {
  int error = 0;
  DecodedGif gif(DGifOpenFileName(path.c_str(), &error));
  if (!gif)
    ADD_FAILURE() << path << ": " << GifErrorString(error);
  else if (DGifSlurp(gif.get()) != GIF_OK) {
    ADD_FAILURE() << path << ": " << GifErrorString(gif->Error);
    gif.reset();
  }
  return gif;
}

TEST(Animation, GifDecodesBackToItsFramesLoopingAtItsRate) {
  test::TempDir dir;
  const std::vector<Image> frames = movingSquare(5, 40, 32, 3);
  ASSERT_TRUE(writeAnimation(dir / "clip.gif", frames, 12));
  const DecodedGif gif = slurpGif(dir / "clip.gif");
  ASSERT_TRUE(gif);
  EXPECT_EQ(gif->SWidth, 40);
  EXPECT_EQ(gif->SHeight, 32);
  ASSERT_EQ(gif->ImageCount, 5);
  bool loops = false;  // the NETSCAPE2.0 extension, before the first frame, with a loop count of 0
  const SavedImage& first = gif->SavedImages[0];
  for (int e = 0; e + 1 < first.ExtensionBlockCount; ++e) {
    const ExtensionBlock& block = first.ExtensionBlocks[e];
    const ExtensionBlock& next = first.ExtensionBlocks[e + 1];
    loops |= block.Function == APPLICATION_EXT_FUNC_CODE && block.ByteCount == 11 &&
             std::string(reinterpret_cast<char*>(block.Bytes), 11) == "NETSCAPE2.0" && next.ByteCount == 3 &&
             next.Bytes[0] == 1 && next.Bytes[1] == 0 && next.Bytes[2] == 0;
  }
  EXPECT_TRUE(loops);
  const std::uint8_t bright = std::uint8_t(std::lround(srgbFromLinear(0.8f) * 255));
  for (int f = 0; f < gif->ImageCount; ++f) {
    const SavedImage& image = gif->SavedImages[f];
    GraphicsControlBlock control;
    ASSERT_EQ(DGifSavedExtensionToGCB(gif.get(), f, &control), GIF_OK);
    EXPECT_EQ(control.DelayTime, 8);  // 100 / 12 hundredths of a second
    const ColorMapObject* palette = image.ImageDesc.ColorMap ? image.ImageDesc.ColorMap : gif->SColorMap;
    ASSERT_NE(palette, nullptr);
    const auto colour = [&](int x, int y) { return palette->Colors[image.RasterBits[y * 40 + x]]; };
    // Two colours in the frame: both exact in its palette.
    EXPECT_EQ(colour(f + 2, 10).Red, bright) << f;  // inside the square
    EXPECT_EQ(colour(f + 2, 10).Green, bright) << f;
    EXPECT_EQ(colour(30, 28).Blue, 0) << f;  // the dark background
  }
}

TEST(Animation, GifOfManyColorsIsQuantisedClosely) {
  test::TempDir dir;
  Image gradient(64, 64, 3);  // 4096 colours: more than one palette holds
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) gradient.at(x, y, 0) = x / 63.0f, gradient.at(x, y, 1) = y / 63.0f;
  std::vector<Image> frames;
  frames.push_back(gradient.copy());
  frames.push_back(std::move(gradient));
  ASSERT_TRUE(writeAnimation(dir / "g.gif", frames, 10));
  const DecodedGif gif = slurpGif(dir / "g.gif");
  ASSERT_TRUE(gif);
  ASSERT_EQ(gif->ImageCount, 2);
  const SavedImage& image = gif->SavedImages[0];
  double sumError = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const GifColorType colour = image.ImageDesc.ColorMap->Colors[image.RasterBits[y * 64 + x]];
      sumError += std::abs(colour.Red - std::lround(srgbFromLinear(x / 63.0f) * 255)) +
                  std::abs(colour.Green - std::lround(srgbFromLinear(y / 63.0f) * 255));
      EXPECT_EQ(colour.Blue, 0);
    }
  // 256 boxes over a 64 x 64 grid of colours: about 16 codes per box side, so a mean error of 4
  // codes at best; giflib's median cut works on 5 bits per channel and lands near 6.
  const double meanError = sumError / (64 * 64 * 2);
  std::printf("[ gif     ] 4096-colour frame: mean error %.2f codes per channel\n", meanError);
  EXPECT_LT(meanError, 8.0);
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
  for (const Status& status : {writeAnimation(dir / "clip.avi", frames, 10), writeAnimation(dir / "clip.mp4", {}, 10),
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
