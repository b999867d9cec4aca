// MP4 videos (animation.hpp): the checks and the frames' pixels here, FFmpeg's part in the module
// liblfcam_mp4.so (render/mp4_codec.hpp), loaded on the first video.
#include <algorithm>
#include <cstdint>
#include <string>

#include "core/atomic_file.hpp"
#include "core/lazy_module.hpp"
#include "io/io_support.hpp"
#include "lfcam/render/animation.hpp"
#include "render/animation_frames.hpp"
#include "render/mp4_codec.hpp"

namespace lfcam {

namespace {

namespace fs = std::filesystem;

Result<const Mp4Codec*> loadMp4Codec(const std::string& purpose) {
  LFCAM_ASSIGN_OR_RETURN(void* table, lazyModuleEntry("mp4", LFCAM_MP4_CODEC_ENTRY, purpose));
  return static_cast<const Mp4Codec*>(table);
}

// The module's error, naming the file.
Error aboutFile(const Error& error, const fs::path& path) { return io::fileError(error.code, path, error.message); }

// Interleaved sRGB 8-bit of `frame`, grown to even sizes by repeating the last column and row.
std::vector<std::uint8_t> evenSizedPixels(const Image& frame, int width, int height) {
  const std::vector<std::uint8_t> pixels = srgb8Interleaved(frame);
  if (width == frame.width() && height == frame.height()) return pixels;
  std::vector<std::uint8_t> grown(std::size_t(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        grown[(std::size_t(y) * width + x) * 3 + c] =
            pixels[(std::size_t(std::min(y, frame.height() - 1)) * frame.width() + std::min(x, frame.width() - 1)) * 3 +
                   c];
  return grown;
}

}  // namespace

Status writeMp4Video(const fs::path& path, const std::vector<Image>& frames, int framesPerSecond) {
  if (io::lowerExtension(path) != ".mp4")
    return makeError(ErrorCode::Usage, path.string() + ": MP4 videos are written as .mp4");
  LFCAM_TRY(checkAnimationFrames(path, frames, framesPerSecond));
  LFCAM_ASSIGN_OR_RETURN(const Mp4Codec* codec, loadMp4Codec(path.string() + ": MP4 export"));
  const int width = frames[0].width() + frames[0].width() % 2, height = frames[0].height() + frames[0].height() % 2;
  const Mp4Frames even{width, height, framesPerSecond, frames.size(),
                       [&](std::size_t i) { return evenSizedPixels(frames[i], width, height); }};
  return writeFileAtomically(path, [&](const fs::path& temporary) -> Status {
    if (Status encoded = codec->encode(temporary, even); !encoded) return aboutFile(encoded.error(), path);
    return {};
  });
}

Result<VideoSummary> readVideoSummary(const fs::path& path) {
  LFCAM_TRY(io::checkReadableFile(path));
  LFCAM_ASSIGN_OR_RETURN(const Mp4Codec* codec, loadMp4Codec(path.string() + ": reading a video"));
  Result<VideoSummary> summary = codec->summarise(path);
  if (!summary) return aboutFile(summary.error(), path);
  return summary;
}

}  // namespace lfcam
