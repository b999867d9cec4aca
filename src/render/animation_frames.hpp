// What the GIF and MP4 writers (animation.cpp, mp4_video.cpp) share: the checks of a frame list
// and the conversion of a frame to interleaved sRGB-encoded 8-bit RGB. Internal to the library.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

// Usage error unless the frames are non-empty, share one size, have 1 or 3 channels, and the
// rate lies in [1, 100] frames per second.
Status checkAnimationFrames(const std::filesystem::path& path, const std::vector<Image>& frames, int framesPerSecond);

// width x height x 3 bytes, rows top to bottom; grey frames repeat into the three channels.
std::vector<std::uint8_t> srgb8Interleaved(const Image& frame);

}  // namespace lfcam
