// The FFmpeg half of MP4 export: it lives in the module liblfcam_mp4.so (src/render/mp4_module/),
// loaded by mp4_video.cpp on first use (core/lazy_module.hpp), so that no other command maps FFmpeg.
// Only types defined in headers cross the boundary; errors say what went wrong, and the caller
// names the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "lfcam/core/result.hpp"
#include "lfcam/render/animation.hpp"

namespace lfcam {

struct Mp4Frames {
  int width = 0, height = 0;  // even
  int framesPerSecond = 0;
  std::size_t count = 0;
  std::function<std::vector<std::uint8_t>(std::size_t)> rgb;  // frame i: width x height x 3 sRGB bytes
};

struct Mp4Codec {
  Status (*encode)(const std::filesystem::path& file, const Mp4Frames& frames);
  Result<VideoSummary> (*summarise)(const std::filesystem::path& file);
};

}  // namespace lfcam

// The module's one export: its table.
#define LFCAM_MP4_CODEC_ENTRY "lfcamMp4Codec"
