// Animated GIFs through giflib, and the choice of format by extension: animation.hpp.
#include "lfcam/render/animation.hpp"

#include <fcntl.h>
#include <gif_lib.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <unordered_map>

#include "core/atomic_file.hpp"
#include "io/io_support.hpp"
#include "lfcam/io/image_io.hpp"
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
        const float encoded = srgbFromLinear(std::clamp(linear, 0.0f, 1.0f));
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

namespace {

// A giflib file handle, closed (and freed) on every path.
struct GifCloser {
  void operator()(GifFileType* gif) const { EGifCloseFile(gif, nullptr); }
};
using GifFile = std::unique_ptr<GifFileType, GifCloser>;

// The NETSCAPE2.0 application extension: loop forever.
bool putLoopForever(GifFileType* gif) {
  static const GifByteType application[] = {'N', 'E', 'T', 'S', 'C', 'A', 'P', 'E', '2', '.', '0'};
  static const GifByteType loop[] = {1, 0, 0};  // sub-block 1, loop count 0 (forever), little-endian
  return EGifPutExtensionLeader(gif, APPLICATION_EXT_FUNC_CODE) == GIF_OK &&
         EGifPutExtensionBlock(gif, sizeof application, application) == GIF_OK &&
         EGifPutExtensionBlock(gif, sizeof loop, loop) == GIF_OK && EGifPutExtensionTrailer(gif) == GIF_OK;
}

// The frame's own colours when it has at most 256 (exact), else false.
bool exactPalette(const std::vector<std::uint8_t>& interleaved, GifColorType (&colors)[256],
                  std::vector<GifByteType>& indices) {
  std::unordered_map<std::uint32_t, GifByteType> index;
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const std::uint8_t* rgb = &interleaved[3 * i];
    const std::uint32_t key = std::uint32_t(rgb[0]) << 16 | std::uint32_t(rgb[1]) << 8 | rgb[2];
    auto [at, added] = index.try_emplace(key, GifByteType(index.size()));
    if (added) {
      if (index.size() > 256) return false;
      colors[at->second] = {rgb[0], rgb[1], rgb[2]};
    }
    indices[i] = at->second;
  }
  return true;
}

// One frame with its own 256-colour palette: its colours when it has no more, else giflib's
// median cut; shown for `delay` hundredths of a second.
bool putFrame(GifFileType* gif, const Image& frame, int delay) {
  const int width = frame.width(), height = frame.height();
  const std::size_t pixels = std::size_t(width) * height;
  const std::vector<std::uint8_t> interleaved = srgb8Interleaved(frame);
  std::vector<GifByteType> indices(pixels);
  GifColorType colors[256] = {};
  if (!exactPalette(interleaved, colors, indices)) {
    std::vector<GifByteType> red(pixels), green(pixels), blue(pixels);
    for (std::size_t i = 0; i < pixels; ++i)
      red[i] = interleaved[3 * i], green[i] = interleaved[3 * i + 1], blue[i] = interleaved[3 * i + 2];
    int colorCount = 256;
    if (GifQuantizeBuffer(unsigned(width), unsigned(height), &colorCount, red.data(), green.data(), blue.data(),
                          indices.data(), colors) == GIF_ERROR)
      return false;
  }
  std::unique_ptr<ColorMapObject, void (*)(ColorMapObject*)> palette(GifMakeMapObject(256, colors), GifFreeMapObject);
  GraphicsControlBlock control{.DisposalMode = DISPOSE_DO_NOT,
                               .UserInputFlag = false,
                               .DelayTime = delay,
                               .TransparentColor = NO_TRANSPARENT_COLOR};
  GifByteType controlBytes[4];
  EGifGCBToExtension(&control, controlBytes);
  if (!palette || EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, sizeof controlBytes, controlBytes) == GIF_ERROR ||
      EGifPutImageDesc(gif, 0, 0, width, height, false, palette.get()) == GIF_ERROR)
    return false;
  for (int y = 0; y < height; ++y)
    if (EGifPutLine(gif, indices.data() + std::size_t(y) * width, width) == GIF_ERROR) return false;
  return true;
}

}  // namespace

Status writeAnimatedGif(const std::filesystem::path& path, const std::vector<Image>& frames, int framesPerSecond) {
  if (io::lowerExtension(path) != ".gif")
    return makeError(ErrorCode::Usage, path.string() + ": animated GIFs are written as .gif");
  LFCAM_TRY(checkAnimationFrames(path, frames, framesPerSecond));
  const int delay = int(std::lround(100.0 / framesPerSecond));  // GIF delays are in hundredths of a second

  return writeFileAtomically(path, [&](const std::filesystem::path& temporary) -> Status {
    // Opened here, not by EGifOpenFileName, so the file gets the usual permissions (0666 less umask).
    const int descriptor = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    if (descriptor < 0) return makeError(ErrorCode::Io, path.string() + ": cannot write: " + std::strerror(errno));
    int error = 0;
    GifFile gif(EGifOpenFileHandle(descriptor, &error));
    if (!gif) ::close(descriptor);
    const auto failed = [&] {
      const char* reason = GifErrorString(gif ? gif->Error : error);
      return makeError(ErrorCode::Io, path.string() + ": cannot write: " + (reason ? reason : "unknown error"));
    };
    if (!gif) return failed();
    EGifSetGifVersion(gif.get(), true);
    if (EGifPutScreenDesc(gif.get(), frames[0].width(), frames[0].height(), 8, 0, nullptr) == GIF_ERROR ||
        !putLoopForever(gif.get()))
      return failed();
    for (const Image& frame : frames)
      if (!putFrame(gif.get(), frame, delay)) return failed();
    if (EGifCloseFile(gif.release(), &error) == GIF_ERROR) return failed();
    return {};
  });
}

}  // namespace lfcam
