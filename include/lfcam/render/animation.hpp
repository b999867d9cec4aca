// Animations of rendered photographs (focus pulls, orbits of the observer): looping GIFs through
// giflib (each frame its own 256-colour palette: exact when it has no more colours, else by
// median cut), and MP4 videos through FFmpeg's libraries
// (H.264 by libx264 when libavcodec has it, else MPEG-4 part 2). Both sRGB-encoded 8-bit.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

// Writes `frames` (linear light, all the same size, 1 or 3 channels) at `framesPerSecond`,
// atomically, in the format of the name's extension: .gif (looping) or .mp4. Usage error for no
// frames, mixed sizes, a frame rate outside [1, 100] or another extension.
Status writeAnimation(const std::filesystem::path& path, const std::vector<Image>& frames, int framesPerSecond);

// The same for one format; the name must end in .gif (or .mp4).
Status writeAnimatedGif(const std::filesystem::path& path, const std::vector<Image>& frames, int framesPerSecond);
// H.264 needs even sizes: an odd width or height gains one column or row repeating the last.
Status writeMp4Video(const std::filesystem::path& path, const std::vector<Image>& frames, int framesPerSecond);

// What a video file holds, found by decoding every frame of its first video stream.
struct VideoSummary {
  int frames = 0;
  int width = 0, height = 0;
  std::string codec;  // FFmpeg's short name: "h264", "mpeg4", ...
};
Result<VideoSummary> readVideoSummary(const std::filesystem::path& path);

}  // namespace lfcam
