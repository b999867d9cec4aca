// Animated GIFs, and the choice of format by extension: animation.hpp.
#include "lfcam/animation.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "io/io_support.hpp"
#include "lfcam/atomic_file.hpp"
#include "lfcam/image_io.hpp"
#include "render/animation_frames.hpp"

namespace lfcam {

Status checkAnimationFrames(const std::filesystem::path& path, const std::vector<Image>& frames, int framesPerSecond) {
  if (frames.empty()) return makeError(ErrorCode::Usage, path.string() + ": no frames to write");
  const int width = frames[0].width(), height = frames[0].height();
  for (const Image& frame : frames)
    if (frame.width() != width || frame.height() != height || frame.empty() ||
        (frame.channels() != 1 && frame.channels() != 3))
      return makeError(ErrorCode::Usage, path.string() + ": frames must share one size and have 1 or 3 channels");
  if (framesPerSecond < 1 || framesPerSecond > 100)
    return makeError(ErrorCode::Usage, path.string() + ": frames per second must lie in [1, 100]");
  return {};
}

std::vector<std::uint8_t> srgb8Interleaved(const Image& frame) {
  const int width = frame.width(), height = frame.height();
  std::vector<std::uint8_t> pixels(std::size_t(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        const float linear = frame.at(x, y, frame.channels() == 1 ? 0 : c);
        const float encoded = linearToSrgb(std::clamp(linear, 0.0f, 1.0f));
        pixels[(std::size_t(y) * width + x) * 3 + c] = std::uint8_t(std::lround(encoded * 255.0f));
      }
  return pixels;
}

Status writeAnimation(const std::filesystem::path& path, const std::vector<Image>& frames, int framesPerSecond) {
  const std::string extension = io::lowerExtension(path);
  if (extension == ".gif") return writeAnimatedGif(path, frames, framesPerSecond);
  if (extension == ".mp4") return writeMp4Video(path, frames, framesPerSecond);
  return makeError(ErrorCode::Usage, path.string() + ": animations are written as .gif or .mp4");
}

Status writeAnimatedGif(const std::filesystem::path& path, const std::vector<Image>& frames, int framesPerSecond) {
  if (io::lowerExtension(path) != ".gif")
    return makeError(ErrorCode::Usage, path.string() + ": animated GIFs are written as .gif");
  LFCAM_TRY(checkAnimationFrames(path, frames, framesPerSecond));
  const int width = frames[0].width(), height = frames[0].height();

  return writeFileAtomically(path, [&](const std::filesystem::path& temporary) -> Status {
    auto out = OIIO::ImageOutput::create(temporary.string());
    if (!out) return makeError(ErrorCode::Unsupported, path.string() + ": this OpenImageIO cannot write GIF");
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    const int rate[2] = {framesPerSecond, 1};
    spec.attribute("FramesPerSecond", OIIO::TypeRational, rate);
    spec.attribute("gif:LoopCount", 0);  // forever
    std::vector<OIIO::ImageSpec> specs(frames.size(), spec);
    if (!out->open(temporary.string(), int(specs.size()), specs.data()))
      return makeError(ErrorCode::Io, path.string() + ": " + out->geterror());
    for (std::size_t f = 0; f < frames.size(); ++f) {
      if (f > 0 && !out->open(temporary.string(), spec, OIIO::ImageOutput::AppendSubimage))
        return makeError(ErrorCode::Io, path.string() + ": " + out->geterror());
      const std::vector<std::uint8_t> pixels = srgb8Interleaved(frames[f]);
      if (!out->write_image(OIIO::TypeDesc::UINT8, pixels.data()))
        return makeError(ErrorCode::Io, path.string() + ": " + out->geterror());
    }
    if (!out->close()) return makeError(ErrorCode::Io, path.string() + ": " + out->geterror());
    return {};
  });
}

}  // namespace lfcam
